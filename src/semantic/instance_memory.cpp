#include "ply_slam/semantic/instance_memory.h"

namespace ply_slam {
namespace {

// Overlap of a with b, as a share of a.
double covered(const cv::Mat& a, const cv::Mat& b) {
  const int area = cv::countNonZero(a);
  return area > 0 ? static_cast<double>(cv::countNonZero(a & b)) / area : 0.0;
}

}  // namespace

std::vector<Instance> InstanceMemory::complete(const std::vector<Instance>& instances,
                                               const cv::Mat& gray) {
  carried_.clear();
  std::vector<Instance> out = instances;
  if (remembered_.empty() || gray_.empty() || gray_.size() != gray.size()) return out;
  std::vector<Instance> previous;
  for (const auto& r : remembered_) previous.push_back(r.instance);
  const std::vector<Instance> moved = carrier_.carry(previous, gray_, gray);
  for (size_t k = 0; k < moved.size(); ++k) {
    if (remembered_[k].age >= max_frames_) continue;
    // Seen again: a current instance of its class covers most of where it went.
    bool seen = false;
    for (const auto& instance : instances)
      if (instance.class_name == moved[k].class_name && covered(moved[k].mask, instance.mask) > 0.3)
        seen = true;
    if (seen) continue;
    Instance carried = moved[k];
    carried.id = next_id_++;
    if (next_id_ > 65535) next_id_ = kFirstCarriedId;
    carried.score = 0.0f;  // not a detection
    carried_.push_back({carried, remembered_[k].age + 1});
    out.push_back(carried);
  }
  return out;
}

void InstanceMemory::remember(const std::vector<Instance>& instances,
                              const std::set<int>& dynamic_ids, const cv::Mat& gray) {
  std::vector<Remembered> next;
  for (const auto& instance : instances) {
    if (!dynamic_ids.count(instance.id)) continue;
    int age = 0;
    for (const auto& c : carried_)
      if (c.instance.id == instance.id) age = c.age;
    next.push_back({instance, age});
  }
  remembered_ = std::move(next);
  gray_ = gray.clone();
}

}  // namespace ply_slam
