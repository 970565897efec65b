// Dense module, octree: a wall with a person in front of it, seen by a camera looking at it.
// The wall ends occupied, the person leaves no occupied voxel (left out as dynamic, or cleared
// by later rays once it walked away), the space between camera and wall is free; class
// colours survive a round trip through a .ot file; the worker queues, drains and rejects.
#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "dense_test_scene.h"
#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/key_frame_cloud_builder.h"
#include "ply_slam/dense/map_export.h"
#include "ply_slam/dense/semantic_octree.h"
#include "ply_slam/dense/voxel_agreement.h"

namespace ply_slam {
namespace {

namespace fs = std::filesystem;
using test::kWalkerDepth;
using test::kWalkerPixels;
using test::kWallDepth;
using test::wallPacket;

DenseOptions testParams() { return test::denseTestParams(1, 0.01); }

struct Scene {
  KeyFrameCloudBuilder builder{testParams(), ClassPalette()};
  SemanticOctree octree{0.05, SemanticOctree::ColourMode::kClass, ClassPalette()};
  void see(const KeyFramePacket& packet) { octree.insert(builder.build(packet)); }
  // +1 occupied, 0 free, -1 unknown.
  int state(const Eigen::Vector3d& p) const {
    const auto& tree = octree.tree();
    const octomap::ColorOcTreeNode* node = tree.search(p.x(), p.y(), p.z());
    if (!node) return -1;
    return tree.isNodeOccupied(node) ? 1 : 0;
  }
};

// World points of the person's surface (the camera at the origin looks along +z).
std::vector<Eigen::Vector3d> walkerSurface() {
  const PinholeCamera camera = test::denseTestCamera();
  std::vector<Eigen::Vector3d> points;
  for (int v = kWalkerPixels.y; v < kWalkerPixels.br().y; v += 3)
    for (int u = kWalkerPixels.x; u < kWalkerPixels.br().x; u += 3)
      points.push_back(camera.backProject({u, v}, kWalkerDepth));
  return points;
}

const Eigen::Vector3d kWallCentre(0.01, 0.01, kWallDepth);
const Eigen::Vector3d kBetween1(0.01, 0.01, 1.0), kBetween2(0.01, 0.01, 2.3);

TEST(SemanticOctree, PersonMarkedDynamicLeavesNoVoxelsAndTheWallIsOccupied) {
  Scene scene;
  // The person stands there in the first two keyframes, then has walked off.
  scene.see(*wallPacket(1, {0, 0, 0}, true, true));
  scene.see(*wallPacket(2, {0.1, 0, 0}, true, true));
  for (const auto& p : walkerSurface()) EXPECT_NE(scene.state(p), 1) << p.transpose();
  scene.see(*wallPacket(3, {-0.1, 0.05, 0}, false, false));
  EXPECT_EQ(scene.state(kWallCentre), 1);
  EXPECT_EQ(scene.state(kBetween1), 0);
  EXPECT_EQ(scene.state(kBetween2), 0);
  for (const auto& p : walkerSurface()) EXPECT_EQ(scene.state(p), 0) << p.transpose();
  // Every occupied voxel is wall.
  const auto voxels = scene.octree.occupiedVoxels();
  ASSERT_FALSE(voxels.empty());
  for (const auto& v : voxels) EXPECT_NEAR(v.centre.z(), 3.025, 1e-6);
}

TEST(SemanticOctree, RaysClearAPersonWhoWalkedAwayWhenNothingIsLeftOut) {
  Scene scene;
  scene.see(*wallPacket(1, {0, 0, 0}, true, false));  // not recognised as moving
  int occupied = 0;
  for (const auto& p : walkerSurface()) occupied += scene.state(p) == 1;
  EXPECT_EQ(occupied, static_cast<int>(walkerSurface().size()));  // a ghost, for now
  EXPECT_EQ(scene.state(kBetween1), 0);
  // One hit (+0.85 log-odds) needs three misses (-0.4 each) to turn free.
  for (long id = 2; id <= 4; ++id) scene.see(*wallPacket(id, {0.02 * id, 0, 0}, false, false));
  for (const auto& p : walkerSurface()) EXPECT_EQ(scene.state(p), 0) << p.transpose();
  EXPECT_EQ(scene.state(kWallCentre), 1);
  EXPECT_EQ(scene.state(kBetween2), 0);
}

TEST(SemanticOctree, RaysBeyondTheMappedRangeClearButMarkNothing) {
  Scene scene;
  scene.see(*wallPacket(1, {0, 0, 0}, true, false));  // a ghost in front of the wall
  // The wall is now seen 2 m farther (a door opened): beyond max_depth (4 m) but within the
  // camera's range (8 m): nothing is mapped there, but the rays clear the ghost.
  for (long id = 2; id <= 4; ++id) {
    auto packet = wallPacket(id, {0.02 * id, 0, 0}, false, false);
    packet->depth.setTo(kWallDepth + 2.0);
    const KeyFrameCloud cloud = scene.builder.build(*packet);
    EXPECT_TRUE(cloud.points->empty());
    EXPECT_EQ(cloud.clearing_rays.size(), 160u * 120u);
    scene.octree.insert(cloud);
  }
  for (const auto& p : walkerSurface()) EXPECT_EQ(scene.state(p), 0) << p.transpose();
  EXPECT_EQ(scene.state(kBetween2), 0);
  EXPECT_EQ(scene.state({0.01, 0.01, kWallDepth + 2.0}), -1);  // the ray's end: not mapped
}

TEST(SemanticOctree, OccupancyThresholdAsksForRepeatedHits) {
  // At 0.88 (log-odds 1.99) a voxel needs three hits (3 x 0.85); two (1.69) are not enough.
  SemanticOctree octree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette(), 0.88);
  const KeyFrameCloudBuilder builder(testParams(), ClassPalette());
  for (long id = 1; id <= 3; ++id) {
    octree.insert(builder.build(*wallPacket(id, {0, 0, 0}, false, false)));
    EXPECT_EQ(octree.isOccupied(kWallCentre), id == 3) << id << " hits";
  }
  EXPECT_THROW(SemanticOctree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette(), 0.4),
               std::invalid_argument);
}

TEST(SemanticOctree, RaysStopShortOfTheirHitByTheMargin) {
  // One keyframe hits a surface voxel, three later rays end one voxel behind it (depth noise,
  // a pose a little off). OctoMap's rays clear the surface voxel; rays that stop 10 cm short
  // of their hit leave it, and still clear a voxel well in front.
  auto onePoint = [](float z) {
    KeyFrameCloud cloud;
    cloud.points = std::make_shared<DenseCloud>();
    pcl::PointXYZRGBL p;
    p.x = p.y = 0.01f;
    p.z = z;
    p.label = ClassPalette::kUnknown;
    cloud.points->push_back(p);
    return cloud;
  };
  for (const double margin : {0.0, 0.1}) {
    SemanticOctree octree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette(), 0.5, margin);
    octree.insert(onePoint(3.02f));  // the surface voxel [3.00, 3.05)
    octree.insert(onePoint(1.02f));  // something that was there once
    for (int k = 0; k < 3; ++k) octree.insert(onePoint(3.07f));
    EXPECT_EQ(octree.isOccupied({0.01, 0.01, 3.02}), margin > 0.0) << "margin " << margin;
    EXPECT_TRUE(octree.isOccupied({0.01, 0.01, 3.07})) << "margin " << margin;
    EXPECT_FALSE(octree.isOccupied({0.01, 0.01, 1.02})) << "margin " << margin;
  }
  EXPECT_THROW(SemanticOctree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette(), 0.5, -0.1),
               std::invalid_argument);
}

TEST(SemanticOctree, VoxelsTakeTheirMajorityClassAndCountTaggedHits) {
  SemanticOctree octree(0.05, SemanticOctree::ColourMode::kClass, ClassPalette());
  const ClassPalette palette;
  KeyFrameCloud cloud;
  cloud.points = std::make_shared<DenseCloud>();
  cloud.tags = std::make_shared<DenseCloud>();
  auto add = [&](float x, const std::string& name, bool tag) {
    pcl::PointXYZRGBL p;
    p.x = x, p.y = 0.01f, p.z = 1.01f;
    p.r = p.g = p.b = 100;
    p.label = palette.label(name);
    cloud.points->push_back(p);
    p.label = tag;
    cloud.tags->push_back(p);
  };
  for (int i = 0; i < 3; ++i) add(0.01f + 0.01f * i, "chair", i == 0);  // voxel A: chair x3, tv
  add(0.04f, "tv", true);
  add(0.31f, "tv", true);  // voxel B: tv, tagged
  octree.insert(cloud);
  const auto voxels = octree.occupiedVoxels();
  ASSERT_EQ(voxels.size(), 2u);
  ASSERT_EQ(octree.numOccupied(), 2u);
  for (const auto& v : voxels) {
    const bool a = v.centre.x() < 0.1;
    EXPECT_EQ(palette.name(v.label), a ? "chair" : "tv");
    EXPECT_EQ(v.colour, palette.colour(v.label));
    EXPECT_EQ(v.hits, a ? 4u : 1u);
    EXPECT_EQ(v.tagged, a ? 2u : 1u);
  }
}

TEST(SemanticOctree, ClassColoursRoundTripThroughTheOtFile) {
  Scene scene;
  scene.see(*wallPacket(1, {0, 0, 0}, true, false));  // person kept: two classes in the tree
  const fs::path dir = fs::temp_directory_path() / ("ply_slam_octree_" + std::to_string(getpid()));
  fs::create_directories(dir);
  DenseMap map(0.01);
  map.insert(scene.builder.build(*wallPacket(1, {0, 0, 0}, true, false)));
  writeDenseMaps(dir.string(), map, scene.octree);
  for (const char* name :
       {"dense_map.pcd", "dense_map.ply", "semantic_octree.ot", "octree.bt", "map_legend.txt"})
    EXPECT_TRUE(fs::exists(dir / name)) << name;

  std::unique_ptr<octomap::AbstractOcTree> read(
      octomap::AbstractOcTree::read((dir / "semantic_octree.ot").string()));
  auto* tree = dynamic_cast<octomap::ColorOcTree*>(read.get());
  ASSERT_NE(tree, nullptr);
  const ClassPalette palette;
  const std::vector<SemanticOctree::Voxel> voxels = scene.octree.occupiedVoxels();
  size_t person = 0, unknown = 0;
  for (const auto& v : voxels) {
    const octomap::ColorOcTreeNode* node = tree->search(v.centre.x(), v.centre.y(), v.centre.z());
    ASSERT_NE(node, nullptr);
    EXPECT_TRUE(tree->isNodeOccupied(node));
    const auto c = node->getColor();
    EXPECT_EQ((ClassColour{c.r, c.g, c.b}), palette.colour(v.label));
    person += v.label == palette.label("person");
    unknown += v.label == ClassPalette::kUnknown;
  }
  EXPECT_GT(person, 0u);
  EXPECT_GT(unknown, 0u);
  EXPECT_EQ(person + unknown, voxels.size());

  octomap::OcTree bt(0.05);
  ASSERT_TRUE(bt.readBinary((dir / "octree.bt").string()));
  size_t bt_occupied = 0;
  for (auto it = bt.begin_leafs(); it != bt.end_leafs(); ++it)
    if (bt.isNodeOccupied(*it)) bt_occupied += size_t(1) << (3 * (16 - it.getDepth()));
  EXPECT_EQ(bt_occupied, voxels.size());
  fs::remove_all(dir);
}

// A file that cannot be written (here a folder in its place; a full disk alike) is named,
// and the other maps are still written.
TEST(SemanticOctree, AMapFileThatCannotBeWrittenIsNamedAndTheOthersWritten) {
  Scene scene;
  scene.see(*wallPacket(1, {0, 0, 0}, true, false));
  const fs::path dir =
      fs::temp_directory_path() / ("ply_slam_octree_fail_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "dense_map.ply");
  DenseMap map(0.01);
  map.insert(scene.builder.build(*wallPacket(1, {0, 0, 0}, true, false)));
  try {
    writeDenseMaps(dir.string(), map, scene.octree);
    ADD_FAILURE() << "a directory in place of dense_map.ply went unnoticed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "dense_map.ply").string()), std::string::npos)
        << e.what();
  }
  for (const char* name : {"dense_map.pcd", "semantic_octree.ot", "octree.bt", "map_legend.txt"})
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;
  fs::remove_all(dir);
}

TEST(DenseMappingWorker, DrainsTheQueueAndSkipsBadPackets) {
  DenseOptions params = testParams();
  params.stride = 2;
  DenseMappingWorker worker(params);
  worker.push(wallPacket(1, {0, 0, 0}, true, true));
  auto broken = wallPacket(2, {0, 0, 0}, false, false);
  broken->depth.release();
  worker.push(broken);
  worker.push(wallPacket(3, {0.1, 0, 0}, false, false));
  worker.finish();
  EXPECT_EQ(worker.rejectedPackets(), 1u);
  EXPECT_NE(worker.firstError().find("keyframe 2"), std::string::npos) << worker.firstError();
  EXPECT_EQ(worker.keyFrameMs().size(), 2u);
  worker.withMaps([](DenseMap& map, const SemanticOctree& octree) {
    EXPECT_EQ(map.numKeyFrames(), 2u);
    EXPECT_GT(map.numGlobalPoints(), 0u);
    EXPECT_GT(octree.numOccupied(), 0u);
  });
  EXPECT_THROW(worker.push(wallPacket(4, {0, 0, 0}, false, false)), std::logic_error);
  worker.finish();  // again: nothing happens
}

// A worker behind the mapping side: a keyframe culled before its turn is dropped unbuilt.
TEST(DenseMappingWorker, KeyFramesCulledWhileQueuedAreNeverBuilt) {
  DenseMappingWorker worker(testParams());
  // Holding the maps, the worker cannot insert its first keyframe: the others stay queued.
  worker.withMaps([&worker](DenseMap&, const SemanticOctree&) {
    for (long id : {1, 2, 3}) worker.push(wallPacket(id, {0.1 * id, 0, 0}, false, false));
    MapUpdate culled;
    culled.erased_keyframes = {2};
    worker.follow(culled);
  });
  worker.finish();
  EXPECT_EQ(worker.droppedUnbuilt(), 1u);
  EXPECT_EQ(worker.keyFrameMs().size(), 2u);
  worker.withMaps([](DenseMap& map, const SemanticOctree&) {
    EXPECT_EQ(map.numKeyFrames(), 2u);
    EXPECT_EQ(map.keyFrames().count(2), 0u);
  });
}

TEST(DenseMappingWorker, PoseUpdateRebuildsTheOctreeAtTheNewPose) {
  DenseMappingWorker worker(testParams());
  worker.push(wallPacket(1, {0, 0, 0}, false, false));
  MapUpdate update;
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = Eigen::Vector3d(0, 0, 1.0);  // the keyframe was 1 m further forward
  update.keyframes.push_back({1, moved.inverse()});
  worker.push(update);
  worker.finish();
  worker.withMaps([](DenseMap&, const SemanticOctree& octree) {
    const auto& tree = octree.tree();
    const auto* old_wall = tree.search(0.01, 0.01, kWallDepth);
    const auto* new_wall = tree.search(0.01, 0.01, kWallDepth + 1.0);
    EXPECT_TRUE(old_wall == nullptr || !tree.isNodeOccupied(old_wall));
    ASSERT_NE(new_wall, nullptr);
    EXPECT_TRUE(tree.isNodeOccupied(new_wall));
  });
}

TEST(VoxelAgreement, StrictAndOneVoxelTolerantShares) {
  auto voxel = [](int x, int y, int z) {
    SemanticOctree::Voxel v;
    v.centre = Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5) * 0.05;
    v.size = 0.05;
    return v;
  };
  // A: 4 voxels; B: 2 of them, one shifted by a voxel, one 3 voxels away.
  const std::vector<SemanticOctree::Voxel> a{voxel(0, 0, 0), voxel(1, 0, 0), voxel(5, 5, 5),
                                             voxel(-3, 2, 0)};
  const std::vector<SemanticOctree::Voxel> b{voxel(0, 0, 0), voxel(1, 0, 0), voxel(6, 5, 5),
                                             voxel(-3, 2, 3)};
  const VoxelAgreement r = compareOccupiedVoxels(a, b, 0.05);
  EXPECT_EQ(r.a, 4u);
  EXPECT_EQ(r.b, 4u);
  EXPECT_EQ(r.both, 2u);
  EXPECT_DOUBLE_EQ(r.iou, 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(r.a_in_b, 0.5);
  EXPECT_DOUBLE_EQ(r.tolerant, 6.0 / 8.0);  // all but (-3, 2, 0) and (-3, 2, 3)
  EXPECT_THROW(compareOccupiedVoxels(a, b, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace ply_slam
