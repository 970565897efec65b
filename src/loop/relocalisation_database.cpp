#include "ply_slam/loop/relocalisation_database.h"

#include <utility>

#include "ply_slam/loop/moving_pixels.h"
#include "ply_slam/loop/vocabulary_identity.h"
#include "ply_slam/loop/vocabulary_path.h"

namespace ply_slam {

RelocalisationDatabase::RelocalisationDatabase(BinaryVocabulary orb, const LoopOptions& loop,
                                               int mask_dilation_px)
    : orb_(std::move(orb)),
      orb_identity_(
          vocabularyIdentity(orb_, vocabularyPath(loop.orb_vocabulary, DescriptorKind::kOrb))),
      database_(orb_.numWords(), 0),
      mover_classes_(loop.dynamic_classes),
      mask_dilation_px_(mask_dilation_px) {}

RelocalisationDatabase RelocalisationDatabase::fromOptions(const LoopOptions& loop,
                                                           int mask_dilation_px) {
  return RelocalisationDatabase(
      BinaryVocabulary::load(vocabularyPath(loop.orb_vocabulary, DescriptorKind::kOrb),
                             DescriptorKind::kOrb),
      loop, mask_dilation_px);
}

void RelocalisationDatabase::add(const KeyFrame& keyframe,
                                 const KeyFrameSegmentation& segmentation) {
  const cv::Mat movers = movingPixels(segmentation.label_image, segmentation.instances,
                                      mover_classes_, mask_dilation_px_);
  add(keyframe.id, keyframe.features.descriptors, offMask(keyframe.features.undistorted, movers));
}

void RelocalisationDatabase::addLoaded(const KeyFrame& keyframe, const KeyFramePlace& place) {
  std::vector<bool> kept(keyframe.features.size());
  for (size_t i = 0; i < kept.size(); ++i) kept[i] = place.uses(i);
  add(keyframe.id, keyframe.features.descriptors, kept);
}

void RelocalisationDatabase::add(long id, const cv::Mat& descriptors,
                                 const std::vector<bool>& kept) {
  KeyFrameWords words;
  words.points = orb_.transform(keptRows(descriptors, kept));
  database_.add(id, std::move(words));
  used_keypoints_[id].assign(kept.begin(), kept.end());
}

void RelocalisationDatabase::remove(long id) {
  database_.remove(id);
  used_keypoints_.erase(id);
}

std::map<long, KeyFramePlace> RelocalisationDatabase::places() const {
  std::map<long, KeyFramePlace> places;
  for (const auto& [id, used] : used_keypoints_) places[id].used_keypoints = used;
  return places;
}

std::vector<long> RelocalisationDatabase::recognise(const cv::Mat& orb_descriptors,
                                                    size_t max_results) const {
  return database_.rankByPoints(orb_.transform(orb_descriptors), max_results);
}

}  // namespace ply_slam
