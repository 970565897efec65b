#include "ply_slam/semantic/instance_memory.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace ply_slam {
namespace {

// A mask's area and bounding box, so that overlaps only look where both can be non-zero.
struct Region {
  explicit Region(const cv::Mat& m)
      : mask(m), box(cv::boundingRect(m)), area(cv::countNonZero(m)) {}
  cv::Mat mask;
  cv::Rect box;
  int area;
};

int overlap(const Region& a, const Region& b) {
  const cv::Rect both = a.box & b.box;
  if (both.empty()) return 0;
  cv::Mat common;
  cv::bitwise_and(a.mask(both), b.mask(both), common);
  return cv::countNonZero(common);
}

// Below this IoU with where a remembered instance went, a detection is not taken for it: a
// walker passing in front of a seated person covers part of them, but is not them.
constexpr double kSameInstanceIou = 0.5;

}  // namespace

std::vector<Instance> InstanceMemory::complete(const std::vector<Instance>& instances,
                                               const cv::Mat& gray) {
  followed_.clear();
  presumed_ids_.clear();
  std::vector<Instance> out = instances;
  if (remembered_.empty() || gray_.empty() || gray_.size() != gray.size()) return out;
  std::vector<Instance> previous;
  for (const auto& r : remembered_) previous.push_back(r.instance);
  const std::vector<Instance> moved = carrier_.carry(previous, gray_, gray);
  std::vector<Region> regions;
  for (const auto& instance : instances) regions.emplace_back(instance.mask);
  for (size_t k = 0; k < moved.size(); ++k) {
    Remembered r = remembered_[k];
    ++r.unmeasured;
    // One measurement can be noise (a seated person flagged once); a run of them is not.
    const bool presume = r.run >= kMinRun;
    // Seen again: instances of its class cover much of where it went; the one that matches
    // it best is taken for it.
    bool seen = false;
    const Instance* same = nullptr;
    double best = kSameInstanceIou;
    const Region where(moved[k].mask);
    for (size_t j = 0; j < instances.size(); ++j) {
      if (instances[j].class_name != moved[k].class_name || where.area == 0) continue;
      const int both = overlap(where, regions[j]);
      seen = seen || both > 0.3 * where.area;
      const double iou = static_cast<double>(both) / (where.area + regions[j].area - both);
      if (iou > best) {
        best = iou;
        same = &instances[j];
      }
    }
    const auto followed = [&](int id) {
      return std::any_of(followed_.begin(), followed_.end(),
                         [id](const Remembered& f) { return f.instance.id == id; });
    };
    if (same && !followed(same->id)) {
      followed_.push_back({*same, 0, r.unmeasured, r.run});
      if (presume) presumed_ids_.insert(same->id);
    }
    if (seen || r.unseen >= max_frames_) continue;
    Instance carried = moved[k];
    carried.id = next_id_++;
    if (next_id_ > 65535) next_id_ = kFirstCarriedId;
    carried.score = 0.0f;  // not a detection
    followed_.push_back({carried, r.unseen + 1, r.unmeasured, r.run});
    if (presume) presumed_ids_.insert(carried.id);
    out.push_back(carried);
  }
  return out;
}

void InstanceMemory::remember(const std::vector<Instance>& instances, const std::set<int>& measured,
                              const std::set<int>& dynamic, const cv::Mat& gray) {
  std::vector<Remembered> next;
  for (const auto& instance : instances) {
    if (!dynamic.count(instance.id)) continue;
    Remembered r{instance, 0, 0, 0};  // new: dynamic without a measurement has no run yet
    for (const auto& f : followed_)
      if (f.instance.id == instance.id) r = {instance, f.unseen, f.unmeasured, f.run};
    if (measured.count(instance.id)) {
      r.run = r.unmeasured == 1 ? r.run + 1 : 1;  // measured in the frame before too?
      r.unmeasured = 0;
    }
    if (r.unmeasured < max_frames_) next.push_back(r);
  }
  remembered_ = std::move(next);
  gray_ = gray;  // the caller's image of this frame, not written afterwards
}

}  // namespace ply_slam
