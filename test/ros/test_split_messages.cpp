// The messages of the two-process split carry what each side sends the other bit for bit: the
// tracker's keyframe and report (MappingJobMsg), and a copy of the map that follows the tracker
// and the mapping side through them alone (serialised as on the wire) equals the map field for
// field on real frames.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "default_vocabularies.h"
#include "map_equality.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/split_messages.h"
#include "ply_slam/semantic/mask_folder_segmenter.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/system.h"
#include "replica_run.h"
#include "shared_data.h"
#include "temp_dir.h"
#include "wire_test_helpers.h"

namespace ply_slam {
namespace {

using test::expectRejectedNaming;
using test::sameImage;
using test::throughWire;

std::string xyzFolder() { return test::sharedPath("data/tum/rgbd_dataset_freiburg1_xyz_37"); }
std::string rpyFolder() { return test::sharedPath("data/tum/rgbd_dataset_freiburg1_rpy_150_349"); }
std::string walkersFolder() { return test::sharedPath("data/dynamic/fr1_rpy_150_349_walkers"); }
SystemConfig fr1Config() {
  return loadConfig(std::string(PLY_SLAM_SOURCE_DIR) + "/config/tum_fr1.yaml");
}

Eigen::Isometry3d somePose(double a) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(a / 3, -2 * a, 0.3);
  return T;
}

cv::Mat someDescriptor(int seed) {
  cv::Mat d(1, 32, CV_8U);
  cv::randu(d, seed, 256);
  return d;
}

// A report with every kind of entry: counts, fits, links to points and lines made and seen.
TrackerReport someReport(long keyframe) {
  TrackerReport r;
  r.points[3] = {5, 2};
  r.points[12] = {1, 0};
  r.lines[4] = 3;
  r.line_fits.push_back({4, {0.1, 0.2, 1.0 / 3.0}, {1, 2, 3}, 0.25, 1e-7});
  r.keyframe = keyframe;
  auto made = std::make_shared<MapPoint>();
  made->id = 20;
  made->position = {1.0 / 7.0, -0.5, 2.25};
  made->normal = Eigen::Vector3d(0.2, -0.1, 1).normalized();
  made->min_distance = 0.3;
  made->max_distance = 4.0 / 3.0;
  made->position_weight = 123.456;
  made->descriptor = someDescriptor(1);
  made->visible = 2;
  made->found = 1;
  made->first_keyframe_id = keyframe;
  r.point_links.push_back({7, 20, made, Eigen::Vector3d::Zero(), 0.0});
  r.point_links.push_back({2, 3, nullptr, {0.5, 0.25, 1.0 / 9.0}, 77.5});
  auto line = std::make_shared<MapLine>();
  line->id = 9;
  line->start = {0, 1, 2};
  line->end = {1.0 / 3.0, 1, 2};
  line->start_weight = 4;
  line->end_weight = 5;
  line->descriptor = someDescriptor(2);
  line->first_keyframe_id = keyframe;
  line->observations = 1;
  line->found = 1;
  r.line_links.push_back({1, 9, line});
  r.line_links.push_back({0, 4, nullptr});
  return r;
}

void expectSameReport(const TrackerReport& a, const TrackerReport& b) {
  EXPECT_EQ(a.keyframe, b.keyframe);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (const auto& [id, c] : b.points) {
    ASSERT_TRUE(a.points.count(id)) << id;
    EXPECT_EQ(a.points.at(id).visible, c.visible);
    EXPECT_EQ(a.points.at(id).found, c.found);
  }
  EXPECT_EQ(a.lines, b.lines);
  ASSERT_EQ(a.line_fits.size(), b.line_fits.size());
  for (size_t i = 0; i < b.line_fits.size(); ++i) {
    const auto &x = a.line_fits[i], &y = b.line_fits[i];
    EXPECT_TRUE(x.id == y.id && x.start == y.start && x.end == y.end &&
                x.start_weight == y.start_weight && x.end_weight == y.end_weight);
  }
  ASSERT_EQ(a.point_links.size(), b.point_links.size());
  for (size_t i = 0; i < b.point_links.size(); ++i) {
    const auto &x = a.point_links[i], &y = b.point_links[i];
    EXPECT_TRUE(x.keypoint == y.keypoint && x.id == y.id && x.measured == y.measured &&
                x.weight == y.weight);
    ASSERT_EQ(x.created != nullptr, y.created != nullptr);
    if (!y.created) continue;
    const MapPoint &p = *x.created, &q = *y.created;
    EXPECT_TRUE(p.id == q.id && p.position == q.position && p.normal == q.normal &&
                p.min_distance == q.min_distance && p.max_distance == q.max_distance &&
                p.position_weight == q.position_weight && p.visible == q.visible &&
                p.found == q.found && p.first_keyframe_id == q.first_keyframe_id);
    EXPECT_TRUE(sameImage(p.descriptor, q.descriptor));
  }
  ASSERT_EQ(a.line_links.size(), b.line_links.size());
  for (size_t i = 0; i < b.line_links.size(); ++i) {
    const auto &x = a.line_links[i], &y = b.line_links[i];
    EXPECT_TRUE(x.line == y.line && x.id == y.id);
    ASSERT_EQ(x.created != nullptr, y.created != nullptr);
    if (!y.created) continue;
    const MapLine &p = *x.created, &q = *y.created;
    EXPECT_TRUE(p.id == q.id && p.start == q.start && p.end == q.end &&
                p.start_weight == q.start_weight && p.end_weight == q.end_weight &&
                p.first_keyframe_id == q.first_keyframe_id && p.observations == q.observations &&
                p.found == q.found);
    EXPECT_TRUE(sameImage(p.descriptor, q.descriptor));
  }
}

TEST(SplitMessages, AReportTravelsBitForBit) {
  const TrackerReport report = someReport(6);
  expectSameReport(fromMsg(throughWire(toMsg(report))), report);
  expectSameReport(fromMsg(throughWire(toMsg(TrackerReport{}))), TrackerReport{});
}

// A keyframe of a real frame (fr1_xyz's first), as the tracker hands it over: features with
// their motion-corrected pixels and depths, a pose, two instances, one of them moving.
class JobTest : public ::testing::Test {
 protected:
  void SetUp() override {
    PLY_SLAM_REQUIRE_SHARED(xyzFolder());
    const TumSequence sequence(xyzFolder());
    images_ = sequence.load(0, config_.camera.depth_factor);
    cv::Mat gray;
    cv::cvtColor(images_.rgb, gray, cv::COLOR_BGR2GRAY);
    auto kf = std::make_shared<KeyFrame>();
    kf->id = 6;
    kf->frame_id = 40;
    kf->stamp = images_.stamp;
    kf->T_cw = somePose(0.3);
    kf->features = FrameFeatures::extract(gray, images_.depth, config_.camera, extractor_);
    kf->features.depth_dt = 0.0123;
    kf->features.depth_image.release();  // as stored
    kf->map_points.resize(kf->features.size());
    kf->map_lines.resize(3);
    job_.keyframe = kf;
    job_.images = images_;
    job_.images.depth_stamp = images_.stamp + 0.0123;
    job_.report = someReport(kf->id);
    job_.followed_updates = 17;
    job_.made_after = kf->id - 2;
    job_.made_after_T_cw = somePose(0.2);
    job_.reference_keyframe = 5;
    job_.loaded_map = 0xfedcba9876543210ULL;
    std::vector<Instance> instances(2);
    instances[0] = {3, "person", 0.9f, cv::Mat::zeros(images_.rgb.size(), CV_8UC1)};
    instances[1] = {8, "chair", 0.5f, cv::Mat::zeros(images_.rgb.size(), CV_8UC1)};
    cv::rectangle(instances[0].mask, cv::Rect(100, 100, 80, 200), 255, cv::FILLED);
    cv::rectangle(instances[1].mask, cv::Rect(150, 250, 100, 100), 255, cv::FILLED);
    cv::Mat dynamic = instances[0].mask.clone();
    job_.segmentation = segmentationOf(instances, {3}, dynamic, images_.rgb.size());
  }

  MappingJob throughMessage(const MappingJob& job) const {
    return fromMsg(throughWire(toMsg(job, "map")), receiver());
  }

  JobReceiver receiver() const {
    return {&extractor_.scales(), cv::Size(config_.camera.width, config_.camera.height)};
  }

  const SystemConfig config_ = fr1Config();
  const OrbExtractor extractor_{config_.orb};
  RgbdImages images_;
  MappingJob job_;
};

TEST_F(JobTest, TravelsBitForBit) {
  const MappingJob back = throughMessage(job_);
  const KeyFrame &a = *back.keyframe, &b = *job_.keyframe;
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.frame_id, b.frame_id);
  EXPECT_EQ(a.stamp, b.stamp);
  EXPECT_TRUE(a.T_cw.matrix() == b.T_cw.matrix());
  const FrameFeatures &f = a.features, &g = b.features;
  ASSERT_GT(g.size(), 500u);
  ASSERT_EQ(f.size(), g.size());
  for (size_t i = 0; i < g.size(); ++i) {
    const cv::KeyPoint &k = f.keypoints[i], &l = g.keypoints[i];
    ASSERT_TRUE(k.pt == l.pt && k.size == l.size && k.angle == l.angle &&
                k.response == l.response && k.octave == l.octave)
        << "keypoint " << i;
    ASSERT_TRUE(f.rectified[i] == g.rectified[i] && f.undistorted[i] == g.undistorted[i] &&
                f.depth[i] == g.depth[i])
        << "keypoint " << i;
  }
  EXPECT_TRUE(sameImage(f.descriptors, g.descriptors));
  EXPECT_EQ(f.scales, &extractor_.scales());
  EXPECT_EQ(f.width, g.width);
  EXPECT_EQ(f.height, g.height);
  EXPECT_EQ(f.depth_dt, g.depth_dt);
  // The search grid is built: the same features in the same area.
  const Eigen::Vector2d& u = g.undistorted[g.size() / 2];
  EXPECT_EQ(f.featuresInArea(u.x(), u.y(), 20, 0, 7), g.featuresInArea(u.x(), u.y(), 20, 0, 7));
  EXPECT_EQ(a.map_points.size(), b.map_points.size());
  EXPECT_EQ(a.map_lines.size(), 3u);
  expectSameReport(back.report, job_.report);
  EXPECT_EQ(back.followed_updates, 17);
  EXPECT_EQ(back.made_after, job_.made_after);
  EXPECT_TRUE(back.made_after_T_cw.isApprox(job_.made_after_T_cw, 1e-12));
  EXPECT_EQ(back.reference_keyframe, 5);
  EXPECT_EQ(back.loaded_map, 0xfedcba9876543210ULL);
  EXPECT_EQ(back.images.stamp, job_.images.stamp);
  EXPECT_EQ(back.images.depth_stamp, job_.images.depth_stamp);
  EXPECT_TRUE(sameImage(back.images.rgb, images_.rgb));
  EXPECT_TRUE(sameImage(back.images.depth, images_.depth));
  EXPECT_TRUE(sameImage(back.segmentation.label_image, job_.segmentation.label_image));
  EXPECT_TRUE(sameImage(back.segmentation.dynamic_mask, job_.segmentation.dynamic_mask));
  ASSERT_EQ(back.segmentation.instances.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const auto &x = back.segmentation.instances[i], &y = job_.segmentation.instances[i];
    EXPECT_TRUE(x.id == y.id && x.class_name == y.class_name && x.score == y.score &&
                x.dynamic == y.dynamic);
  }
}

TEST_F(JobTest, InconsistentJobsAreRejected) {
  const MappingJobMsg good = toMsg(job_, "map");
  const JobReceiver here = receiver();
  MappingJobMsg msg = good;
  msg.descriptors.pop_back();
  expectRejectedNaming([&] { fromMsg(msg, here); }, "descriptors");
  msg = good;
  msg.features[5].octave = static_cast<int>(here.scales->size());
  expectRejectedNaming([&] { fromMsg(msg, here); }, "outside the pyramid");
  msg = good;
  msg.report.point_links[0].keypoint = static_cast<uint32_t>(good.features.size());
  expectRejectedNaming([&] { fromMsg(msg, here); }, "keypoint");
  msg = good;
  msg.line_slots = 1;
  expectRejectedNaming([&] { fromMsg(msg, here); }, "line 1 of 1");
  msg = good;
  msg.report.keyframe = 5;
  expectRejectedNaming([&] { fromMsg(msg, here); }, "report is of keyframe 5");
  msg = good;
  msg.report.point_links[0].created[0].id = 21;
  expectRejectedNaming([&] { fromMsg(msg, here); }, "another landmark");
  msg = good;
  msg.report.point_links[0].created[0].position.x = std::nan("");
  expectRejectedNaming([&] { fromMsg(msg, here); }, "not finite");
  msg = good;
  msg.features[0].u = std::numeric_limits<double>::infinity();
  expectRejectedNaming([&] { fromMsg(msg, here); }, "not finite");
  msg = good;
  msg.made_after = msg.id;  // not one made before it
  expectRejectedNaming([&] { fromMsg(msg, here); },
                       "made after keyframe " + std::to_string(msg.id));
  msg = good;
  msg.made_after_T_cw.matrix[0] = 2.0;
  expectRejectedNaming([&] { fromMsg(msg, here); }, "rotation");
  msg = good;
  msg.T_cw.matrix[5] = 0.0;
  expectRejectedNaming([&] { fromMsg(msg, here); }, "rotation");
  msg = good;
  msg.depth.encoding = "16UC1";
  expectRejectedNaming([&] { fromMsg(msg, here); }, "depth");
  msg = good;
  msg.image_width = 1 << 30;  // (the fuzzer's: a grid of that size did not fit in memory)
  expectRejectedNaming([&] { fromMsg(msg, here); }, "features' image is 1073741824x480");
  msg = good;
  msg.rgb = toMsg(job_, "map").dynamic_mask;  // 640x480 mono8: not bgr8
  expectRejectedNaming([&] { fromMsg(msg, here); }, "rgb");
  JobReceiver smaller = here;
  smaller.image_size = cv::Size(320, 240);
  expectRejectedNaming([&] { fromMsg(good, smaller); }, "the camera here 320x240");
}

// Every report and keyframe reaches the follower through MappingJobMsg, every update through
// MapUpdateMsg, both serialised: the follower equals the map after every keyframe.
class SerialisingWire : public test::ReplicaRun::Wire {
 public:
  explicit SerialisingWire(JobReceiver receiver) : receiver_(receiver) {}
  MappingJob toMapper(MappingJob job) override {
    return fromMsg(throughWire(toMsg(job, "map"), &job_bytes), receiver_);
  }
  MapUpdate toTracker(MapUpdate update) override {
    return fromMsg(throughWire(toMsg(update, "map"), &update_bytes));
  }
  size_t job_bytes = 0, update_bytes = 0;

 private:
  const JobReceiver receiver_;
};

TEST(SplitMessages, AMapFollowsTheTrackerAndTheMapperThroughTheirMessages) {
  PLY_SLAM_REQUIRE_SHARED(rpyFolder());
  SystemConfig config = fr1Config();
  config.lines.enabled = true;
  config.loop.enabled = false;
  const TumSequence sequence(rpyFolder());
  const OrbExtractor scales_of(config.orb);
  SerialisingWire wire({&scales_of.scales(), cv::Size(config.camera.width, config.camera.height)});
  test::ReplicaRun run(config, 1, &wire);
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    run.process(static_cast<long>(i), sequence.load(i, config.camera.depth_factor));
    if (HasFatalFailure()) return;
  }
  std::cout << run.keyframes << " keyframes, " << run.changes << " changes journaled; "
            << wire.job_bytes / 1024 << " KiB of keyframes and reports, "
            << wire.update_bytes / 1024 << " KiB of updates\n";
  EXPECT_GE(run.keyframes, 8);
  EXPECT_GT(run.line_fits, 100);
  EXPECT_GT(run.changes, 1000);
}

// A tracking side alone (MappingMode::kApart) and a mapping side of its own (MappingSide), joined
// only by their messages serialised as on the wire (as tracking_node and mapping_node run them),
// track and map as the split system does in one process: every frame's state and pose, the
// keyframes where it put them, both maps field for field.
TEST(SplitMessages, ATrackerAndAMappingSideApartRunAsTheSplitSystem) {
  PLY_SLAM_REQUIRE_SHARED(rpyFolder());
  SystemConfig config = fr1Config();
  config.lines.enabled = true;
  config.loop.enabled = false;
  const TumSequence sequence(rpyFolder());
  System split(config, MappingMode::kSplit), apart(config, MappingMode::kApart);
  MappingSide mapping(config, true, true);
  const OrbExtractor scales_of(config.orb);
  std::deque<MappingJob> jobs;
  apart.setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
  size_t bytes = 0, keyframes = 0, culled = 0;
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const FrameResult a = split.process(images), b = apart.process(images);
    ASSERT_EQ(a.tracking.state, b.tracking.state) << "frame " << i;
    ASSERT_TRUE(a.tracking.T_cw.matrix() == b.tracking.T_cw.matrix()) << "frame " << i;
    ASSERT_EQ(jobs.size(), a.mapped.size()) << "frame " << i;
    for (; !jobs.empty(); jobs.pop_front()) {
      const MappingJob job = fromMsg(throughWire(toMsg(jobs.front(), "map"), &bytes),
                                     {&scales_of.scales(), images.rgb.size()});
      const MappedKeyFrame mapped = mapping.mapKeyFrame(job);
      apart.followMapUpdate(fromMsg(throughWire(toMsg(*mapped.map_update, "map"), &bytes)));
      ++keyframes;
      culled += mapped.map_update->erased_keyframes.size();
    }
  }
  std::cout << keyframes << " keyframes (" << culled << " culled), " << bytes / (1 << 20)
            << " MiB through the wire\n";
  EXPECT_GE(keyframes, 8u);
  test::expectSameTrajectory(apart.keyFrameTrajectory(), split.keyFrameTrajectory());
  test::expectSameMap(mapping.map(), split.map(), "the mapping sides after 120 frames");
  test::expectSameMap(apart.trackerMap(), split.trackerMap(), "the trackers' copies");
  // The tracked frames hang from the keyframes as tracked, bit for bit, but for those that hung
  // from a keyframe the mapping side culled: the split system moves them to a live keyframe as
  // it culls (after local BA), the tracker apart as it follows (its copy before local BA), so
  // they differ by what local BA moved the two keyframes (measured: 0.64 mm, 5 frames of 120).
  const Trajectory ta = apart.cameraTrajectory(), ts = split.cameraTrajectory();
  ASSERT_EQ(ta.size(), ts.size());
  size_t same = 0;
  double worst = 0.0;
  for (size_t i = 0; i < ta.size(); ++i) {
    same += ta[i].T_wc.matrix() == ts[i].T_wc.matrix();
    worst = std::max(worst, (ta[i].T_wc.translation() - ts[i].T_wc.translation()).norm());
  }
  EXPECT_GE(same, ta.size() - 10 * culled);
  EXPECT_LT(worst, 2e-3);
}

TEST(SplitMessages, ATrackerApartNeedsAJobSinkAndSavesNoMap) {
  SystemConfig config = fr1Config();
  System apart(config, MappingMode::kApart);
  RgbdImages images;
  images.stamp = 1.0;
  images.rgb = cv::Mat::zeros(config.camera.height, config.camera.width, CV_8UC3);
  images.depth = cv::Mat::zeros(config.camera.height, config.camera.width, CV_32FC1);
  EXPECT_THROW(apart.process(images), std::logic_error);
  EXPECT_THROW(apart.saveMap("/tmp/never"), std::logic_error);
  EXPECT_THROW(apart.loadMap("/tmp/never"), std::runtime_error);  // no map file there
  EXPECT_EQ(apart.loopCounts(), nullptr);
}

// Apart, the tracker relocalises through a place database of its own (the mapping side's is in
// the other process): it keeps the words the mapping side keeps (features on people left out)
// and gives the same candidates, here for every keyframe's image of the walkers sequence.
TEST(SplitMessages, ATrackerApartRecognisesPlacesAsTheMappingSide) {
  PLY_SLAM_REQUIRE_SHARED(walkersFolder());
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  SystemConfig config = fr1Config();
  config.loop.enabled = true;
  const TumSequence sequence(walkersFolder());
  MaskFolderSegmenter masks(walkersFolder());
  System apart(config, MappingMode::kApart);
  MappingSide mapping(config, true, true);
  const OrbExtractor scales_of(config.orb);
  std::deque<MappingJob> jobs;
  apart.setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
  size_t with_people = 0, culled = 0;
  for (size_t i = 0; i < sequence.size() && i < 120; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    apart.process(images, masks.segment(images));
    for (; !jobs.empty(); jobs.pop_front()) {
      with_people += !jobs.front().segmentation.instances.empty();
      const MappingJob job = fromMsg(throughWire(toMsg(jobs.front(), "map")),
                                     {&scales_of.scales(), images.rgb.size()});
      const MappedKeyFrame mapped = mapping.mapKeyFrame(job);
      apart.followMapUpdate(fromMsg(throughWire(toMsg(*mapped.map_update, "map"))));
      culled += mapped.map_update->erased_keyframes.size();
    }
  }
  const auto keyframes = mapping.map().keyFrames();
  std::cout << keyframes.size() << " keyframes (" << culled << " culled), " << with_people
            << " handed over with people in them\n";
  EXPECT_GE(with_people, 5u);
  size_t itself_first = 0;
  for (const auto& kf : keyframes) {
    const std::vector<long> found = apart.placeCandidates(kf->features.descriptors);
    EXPECT_EQ(found, mapping.mapper().recognise(kf->features.descriptors,
                                                System::kRelocalisationCandidates))
        << "keyframe " << kf->id;
    itself_first += !found.empty() && found.front() == kf->id;
  }
  EXPECT_GE(itself_first, keyframes.size() * 9 / 10);
}

// A saved map loaded apart: the tracker's copy and the mapping side each from the file, as
// tracking_node and mapping_node with the same ~map. They relocalise and extend it as the split
// system that loaded it does in one process, bit for bit, and give the same place candidates
// for the loaded keyframes; a job from a tracker in another map is refused, the side unchanged.
TEST(SplitMessages, ATrackerAndAMappingSideApartStartFromOneSavedMap) {
  PLY_SLAM_REQUIRE_SHARED(rpyFolder());
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  SystemConfig config = fr1Config();
  config.loop.enabled = true;
  const TumSequence sequence(rpyFolder());
  const TempDir saved;
  constexpr size_t kMapped = 40, kLater = 90;
  {
    System mapper(config);
    for (size_t i = 0; i < kMapped; ++i)
      mapper.process(sequence.load(i, config.camera.depth_factor));
    mapper.saveMap(saved.path().string());
  }
  const std::string file = saved.file(System::kMapFileName);
  System split(config, MappingMode::kSplit), apart(config, MappingMode::kApart);
  split.loadMap(saved.path().string(), false);
  apart.loadMap(saved.path().string(), false);
  const OrbExtractor scales_of(config.orb);
  MappingSide mapping(config, true, true), empty(config, true, true);
  mapping.loadMap(file, &scales_of.scales());
  const size_t loaded = mapping.map().numKeyFrames();
  ASSERT_GE(loaded, 4u);
  EXPECT_NE(mapping.loadedMap(), 0u);
  EXPECT_THROW(mapping.loadMap(file, &scales_of.scales()), std::logic_error);  // not empty
  for (const auto& kf : mapping.map().keyFrames())
    EXPECT_EQ(
        apart.placeCandidates(kf->features.descriptors),
        mapping.mapper().recognise(kf->features.descriptors, System::kRelocalisationCandidates))
        << "loaded keyframe " << kf->id;

  std::deque<MappingJob> jobs;
  apart.setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
  size_t keyframes = 0, first_tracked = kLater;
  for (size_t i = kMapped; i < kLater; ++i) {
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const FrameResult a = split.process(images), b = apart.process(images);
    ASSERT_EQ(a.tracking.state, b.tracking.state) << "frame " << i;
    ASSERT_TRUE(a.tracking.T_cw.matrix() == b.tracking.T_cw.matrix()) << "frame " << i;
    if (b.tracking.state == TrackingState::kOk) first_tracked = std::min(first_tracked, i);
    ASSERT_EQ(jobs.size(), a.mapped.size()) << "frame " << i;
    for (; !jobs.empty(); jobs.pop_front()) {
      const MappingJob job = fromMsg(throughWire(toMsg(jobs.front(), "map")),
                                     {&scales_of.scales(), images.rgb.size()});
      if (keyframes++ == 0) {  // the first job also to a side that started empty: refused
        try {
          empty.mapKeyFrame(job);
          ADD_FAILURE() << "a job made in a loaded map was mapped in an empty one";
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("no map file"), std::string::npos) << e.what();
          EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
        }
        EXPECT_EQ(empty.map().numKeyFrames(), 0u);
        EXPECT_EQ(empty.map().numMapPoints(), 0u);
      }
      apart.followMapUpdate(
          fromMsg(throughWire(toMsg(*mapping.mapKeyFrame(job).map_update, "map"))));
    }
  }
  std::cout << loaded << " keyframes loaded, tracked from frame " << first_tracked << ", "
            << keyframes << " keyframes added apart\n";
  EXPECT_EQ(first_tracked, kMapped);  // relocalised at once: the map saw the frames before
  EXPECT_GE(keyframes, 3u);
  EXPECT_GT(mapping.map().numKeyFrames(), loaded);
  test::expectSameTrajectory(apart.keyFrameTrajectory(), split.keyFrameTrajectory());
  test::expectSameMap(mapping.map(), split.map(), "the mapping sides");
  test::expectSameMap(apart.trackerMap(), split.trackerMap(), "the trackers' copies");
}

// A mapping side that starts anew while the tracker apart goes on (mapping_node restarted): the
// first one maps 30 frames, then is gone for 15 (their jobs lost), then a new one takes over the
// tracker's copy (System::handOverMap) and maps the rest. The copy follows the new side's
// updates, and the two end with the same map, field for field, the keyframes made while no
// mapping side ran included.
TEST(SplitMessages, AMappingSideThatStartsAnewTakesOverTheTrackersCopy) {
  PLY_SLAM_REQUIRE_SHARED(rpyFolder());
  SystemConfig config = fr1Config();
  config.loop.enabled = false;
  const TumSequence sequence(rpyFolder());
  System apart(config, MappingMode::kApart);
  std::deque<MappingJob> jobs;
  apart.setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
  const OrbExtractor scales_of(config.orb);
  auto first = std::make_unique<MappingSide>(config, true, true);
  std::unique_ptr<MappingSide> second;
  constexpr size_t kDown = 30, kUp = 45, kCompareFrom = 70, kEnd = 110;
  size_t lost_jobs = 0, mapped_after = 0, handed_over = 0;
  for (size_t i = 0; i < kEnd; ++i) {
    if (i == kDown) first.reset();
    if (i == kUp) {
      second = std::make_unique<MappingSide>(config, true, true);
      MapSnapshot sent;  // as tracking_node's ~hand_over_map sends it
      sent.handover = apart.handOverMap();
      const MapHandover handover = fromMsg(throughWire(toMsg(sent, "map"))).handover;
      EXPECT_EQ(handover.map_file, sent.handover.map_file);
      EXPECT_GT(handover.updates_followed, 0);
      second->takeOver(handover, &scales_of.scales());
      handed_over = second->map().numKeyFrames();
      EXPECT_THROW(second->takeOver(handover, &scales_of.scales()), std::logic_error);
    }
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    ASSERT_EQ(apart.process(images).tracking.state, TrackingState::kOk) << "frame " << i;
    MappingSide* mapping = first ? first.get() : second.get();
    const size_t mapped_before = mapped_after;
    for (; !jobs.empty(); jobs.pop_front()) {
      if (!mapping) {
        ++lost_jobs;
        continue;
      }
      const MappingJob job = fromMsg(throughWire(toMsg(jobs.front(), "map")),
                                     {&scales_of.scales(), images.rgb.size()});
      apart.followMapUpdate(
          fromMsg(throughWire(toMsg(*mapping->mapKeyFrame(job).map_update, "map"))));
      mapped_after += mapping == second.get();
    }
    // Compared right after a keyframe: the copy's counts since then are not reported yet.
    if (i >= kCompareFrom && mapped_after != mapped_before) break;
  }
  std::cout << lost_jobs << " jobs lost while no mapping side ran, " << handed_over
            << " keyframes handed over, " << mapped_after << " mapped after\n";
  EXPECT_GE(lost_jobs, 2u);
  EXPECT_GE(mapped_after, 3u);
  // A handover that says it followed a negative number of updates is refused by name.
  MapSnapshotMsg bad;
  bad.updates_followed = -1;
  expectRejectedNaming([&] { fromMsg(bad); }, "updates_followed");
  test::expectSameMap(second->map(), apart.trackerMap(), "the new mapping side and the copy");
}

// The ids a map taken over gives next are those the giver would have given: ids of landmarks it
// erased (above every one it kept) are not given again.
TEST(SplitMessages, ATrackerTakingOverAMapGoesOnAfterItsIds) {
  System tracker(fr1Config(), MappingMode::kApart);
  MapHandover handover;  // an empty map whose giver had made and erased a few
  handover.next_ids = {40, 5000, 70};
  tracker.takeOverMap(handover, false);
  const Map::Ids ids = tracker.trackerMap().nextIds();
  EXPECT_EQ(ids.keyframe, 40);
  EXPECT_EQ(ids.point, 5000);
  EXPECT_EQ(ids.line, 70);
}

// A tracker apart that starts anew while the mapping side goes on (tracking_node restarted): the
// first tracker runs 45 frames, then a new one takes over the mapping side's map
// (MappingSide::handOverMap), relocalises at once in it and tracks and extends it with the same
// mapping side. The mapping side's map and the new tracker's copy end the same, field for field,
// and no id of the first tracker's is given again.
TEST(SplitMessages, ATrackerThatStartsAnewTakesOverTheMappingSidesMap) {
  PLY_SLAM_REQUIRE_SHARED(rpyFolder());
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kOrb));
  PLY_SLAM_REQUIRE_VOCABULARY(vocabularyPath("", DescriptorKind::kLbd));
  SystemConfig config = fr1Config();
  config.loop.enabled = true;
  const TumSequence sequence(rpyFolder());
  const OrbExtractor scales_of(config.orb);
  MappingSide mapping(config, true, true);
  constexpr size_t kRestart = 45, kCompareFrom = 70, kEnd = 110;
  auto tracker = std::make_unique<System>(config, MappingMode::kApart);
  std::deque<MappingJob> jobs;
  Map::Ids ids_before;
  size_t first_tracked = kEnd, mapped_after = 0;
  for (size_t i = 0; i < kEnd; ++i) {
    if (i == kRestart) {
      ids_before = tracker->trackerMap().nextIds();
      tracker = std::make_unique<System>(config, MappingMode::kApart);
      MapSnapshot sent;  // the same fields as ~map_for_tracker's answer
      sent.handover = mapping.handOverMap();
      tracker->takeOverMap(fromMsg(throughWire(toMsg(sent, "map"))).handover, false);
      EXPECT_THROW(tracker->takeOverMap(sent.handover, false), std::logic_error);  // not empty
    }
    tracker->setJobSink([&jobs](MappingJob job) { jobs.push_back(std::move(job)); });
    const size_t jobs_before = mapped_after;
    const RgbdImages images = sequence.load(i, config.camera.depth_factor);
    const FrameResult r = tracker->process(images);
    if (i >= kRestart && r.tracking.state == TrackingState::kOk)
      first_tracked = std::min(first_tracked, i);
    for (; !jobs.empty(); jobs.pop_front()) {
      const MappingJob job = fromMsg(throughWire(toMsg(jobs.front(), "map")),
                                     {&scales_of.scales(), images.rgb.size()});
      tracker->followMapUpdate(
          fromMsg(throughWire(toMsg(*mapping.mapKeyFrame(job).map_update, "map"))));
      mapped_after += i >= kRestart;
    }
    // Compared right after a keyframe: the copy's counts since then are not reported yet.
    if (i >= kCompareFrom && jobs_before != mapped_after) break;
  }
  std::cout << "the new tracker tracked from frame " << first_tracked << ", " << mapped_after
            << " keyframes mapped after the restart\n";
  EXPECT_EQ(first_tracked, kRestart);
  EXPECT_GE(mapped_after, 3u);
  // Ids of points the first tracker made and the mapping side erased are not given again.
  for (const auto& p : mapping.map().mapPoints()) {
    if (p->first_keyframe_id >= ids_before.keyframe) {
      EXPECT_GE(p->id, ids_before.point);
    }
  }
  test::expectSameMap(tracker->trackerMap(), mapping.map(), "the new tracker's copy");
}

}  // namespace
}  // namespace ply_slam
