// UnpairedImages: the images the synchroniser drops for want of a partner are named, once each,
// and a dead partner stream cannot make it grow (tracking_node's "unpaired" input).
#include <gtest/gtest.h>

#include "ply_slam/ros/unpaired_images.h"

namespace ply_slam {
namespace {

TEST(UnpairedImages, PairedImagesLeaveNothing) {
  UnpairedImages images(10);
  for (double t : {1.0, 2.0, 3.0}) {
    EXPECT_FALSE(images.arrived(t));
    EXPECT_TRUE(images.paired(t).empty());
  }
  EXPECT_EQ(images.waiting(), 0u);
}

TEST(UnpairedImages, AnImagePassedOverIsNamedOnce) {
  UnpairedImages images(10);
  images.arrived(1.0);
  images.arrived(1.5);  // its depth image never came
  images.arrived(2.0);
  EXPECT_TRUE(images.paired(1.0).empty());
  EXPECT_EQ(images.paired(2.0), std::vector<double>{1.5});
  EXPECT_TRUE(images.paired(3.0).empty());
  EXPECT_EQ(images.waiting(), 0u);
}

TEST(UnpairedImages, LaterArrivalsMayStillBePaired) {
  UnpairedImages images(10);
  images.arrived(2.0);
  images.arrived(3.0);
  images.arrived(1.0);  // out of order, after the pair at 2.0: not passed over
  EXPECT_TRUE(images.paired(2.0).empty());
  EXPECT_TRUE(images.paired(1.0).empty());
  EXPECT_EQ(images.waiting(), 1u);  // 3.0
}

TEST(UnpairedImages, ADeadPartnerStreamIsBounded) {
  UnpairedImages images(3);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(images.arrived(i));
  EXPECT_EQ(images.arrived(3.0), 0.0);
  EXPECT_EQ(images.arrived(4.0), 1.0);
  EXPECT_EQ(images.waiting(), 3u);
}

}  // namespace
}  // namespace ply_slam
