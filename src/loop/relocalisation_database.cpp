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
  const FrameFeatures& features = keyframe.features;
  KeyFrameWords words;
  words.points =
      orb_.transform(keptRows(features.descriptors, offMask(features.undistorted, movers)));
  database_.add(keyframe.id, std::move(words));
}

void RelocalisationDatabase::addLoaded(const KeyFrame& keyframe, const KeyFramePlace& place) {
  const FrameFeatures& features = keyframe.features;
  std::vector<bool> kept(features.size());
  for (size_t i = 0; i < kept.size(); ++i) kept[i] = place.uses(i);
  KeyFrameWords words;
  words.points = orb_.transform(keptRows(features.descriptors, kept));
  database_.add(keyframe.id, std::move(words));
}

void RelocalisationDatabase::remove(long id) { database_.remove(id); }

std::vector<long> RelocalisationDatabase::recognise(const cv::Mat& orb_descriptors,
                                                    size_t max_results) const {
  return database_.rankByPoints(orb_.transform(orb_descriptors), max_results);
}

}  // namespace ply_slam
