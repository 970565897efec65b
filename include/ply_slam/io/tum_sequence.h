#pragma once

#include <string>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/io/rgbd_images.h"

namespace ply_slam {

// One RGB image and the depth image associated with it.
struct RgbdRecord {
  double rgb_stamp = 0.0;
  std::string rgb_path;  // absolute or relative to the working directory
  double depth_stamp = 0.0;
  std::string depth_path;
};

// A folder in the TUM RGB-D layout: rgb.txt, depth.txt, optional associations.txt and
// groundtruth.txt. Without associations.txt every rgb frame is paired with the depth
// image nearest in time (within max_stamp_difference); frames with none are skipped
// and counted. Every problem throws std::runtime_error naming the file and the fault.
class TumSequence {
 public:
  explicit TumSequence(const std::string& folder, double max_stamp_difference = 0.02);

  const std::string& folder() const { return folder_; }
  size_t size() const { return records_.size(); }
  const RgbdRecord& record(size_t i) const { return records_.at(i); }
  const std::vector<RgbdRecord>& records() const { return records_; }
  // rgb frames that found no depth image within max_stamp_difference.
  size_t unassociatedRgbFrames() const { return unassociated_; }
  bool usedAssociationsFile() const { return used_associations_file_; }

  bool hasGroundTruth() const { return !ground_truth_.empty(); }
  const Trajectory& groundTruth() const { return ground_truth_; }
  // Why a groundtruth.txt that is there gives no ground truth (a directory, a named pipe, no
  // poses in it), naming the file; empty when it gives one or is not there.
  const std::string& groundTruthProblem() const { return ground_truth_problem_; }

  // Reads frame i. depth_factor converts 16-bit depth to metres (TUM: 5000).
  // Throws naming the file when an image is missing, unreadable, of the wrong type
  // (rgb must be 8-bit colour, depth 16-bit single channel) or of mismatched size.
  RgbdImages load(size_t i, double depth_factor) const;

 private:
  void readGroundTruth(const std::string& path);

  std::string folder_;
  std::vector<RgbdRecord> records_;
  Trajectory ground_truth_;
  std::string ground_truth_problem_;
  size_t unassociated_ = 0;
  bool used_associations_file_ = false;
};

}  // namespace ply_slam
