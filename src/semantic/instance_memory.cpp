#include "ply_slam/semantic/instance_memory.h"

#include <algorithm>

namespace ply_slam {
namespace {

// Overlap of a with b, as a share of a.
double covered(const cv::Mat& a, const cv::Mat& b) {
  const int area = cv::countNonZero(a);
  return area > 0 ? static_cast<double>(cv::countNonZero(a & b)) / area : 0.0;
}

double iou(const cv::Mat& a, const cv::Mat& b) {
  const int either = cv::countNonZero(a | b);
  return either > 0 ? static_cast<double>(cv::countNonZero(a & b)) / either : 0.0;
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
    for (const auto& instance : instances) {
      if (instance.class_name != moved[k].class_name) continue;
      seen = seen || covered(moved[k].mask, instance.mask) > 0.3;
      const double overlap = iou(moved[k].mask, instance.mask);
      if (overlap > best) {
        best = overlap;
        same = &instance;
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
    Remembered r{instance, 0, 0, 1};
    for (const auto& f : followed_)
      if (f.instance.id == instance.id) r = {instance, f.unseen, f.unmeasured, f.run};
    if (measured.count(instance.id)) {
      r.run = r.unmeasured == 1 ? r.run + 1 : 1;  // measured in the frame before too?
      r.unmeasured = 0;
    }
    if (r.unmeasured < max_frames_) next.push_back(r);
  }
  remembered_ = std::move(next);
  gray_ = gray.clone();
}

}  // namespace ply_slam
