#pragma once

// The messages of the two-process split (issue 17): what the tracker sends the mapping side
// (MappingJobMsg: its keyframe, its report, the images), bit for bit: the mapping side gets the
// doubles the tracker had. (The way back is MapUpdateMsg, conversions.h.)
#include <ply_slam/MappingJobMsg.h>
#include <ply_slam/TrackerReportMsg.h>

#include <string>
#include <vector>

#include "ply_slam/map/tracker_report.h"
#include "ply_slam/system/mapping_job.h"

namespace ply_slam {

TrackerReportMsg toMsg(const TrackerReport& report);
// Throws std::invalid_argument on a number that is not finite or a created landmark whose id
// is not its link's.
TrackerReport fromMsg(const TrackerReportMsg& msg);

// A job with its keyframe (the mapping side's unlinked copy); `world_frame` goes into
// header.frame_id. The sequence number is the sender's.
MappingJobMsg toMsg(const MappingJob& job, const std::string& world_frame);

// What the receiving side checks a job against and makes its keyframe with.
struct JobReceiver {
  const std::vector<double>* scales = nullptr;  // the ORB pyramid's scale per level (its
                                                // extractor's, which outlives the keyframes)
  cv::Size image_size;                          // its camera's
};
// Throws std::invalid_argument on an inconsistent message: an image size other than the
// receiver's camera's (features or images), descriptor rows against features, a feature's level
// outside the pyramid, a link naming a keypoint or line the keyframe has not, a number that is
// not finite, image encodings other than toMsg's.
MappingJob fromMsg(const MappingJobMsg& msg, const JobReceiver& receiver);

}  // namespace ply_slam
