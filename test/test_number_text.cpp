// Numbers typed on the command line: all of the text or nothing.
#include <gtest/gtest.h>

#include <climits>

#include "ply_slam/common/number_text.h"

namespace ply_slam {
namespace {

TEST(NumberText, WholeNumbersWithinTheirRange) {
  EXPECT_EQ(parseWholeNumber("12", 1, 100), 12);
  EXPECT_EQ(parseWholeNumber("-3", -5, 5), -3);
  EXPECT_EQ(parseWholeNumber("0", 0, 0), 0);
  EXPECT_EQ(parseWholeNumber("1", 1, 1), 1);
  for (const char* bad : {"", "12x", "1.5", "1e3", " 5", "5 ", "x", "+", "0x10"})
    EXPECT_FALSE(parseWholeNumber(bad, LONG_MIN, LONG_MAX)) << "'" << bad << "'";
  EXPECT_FALSE(parseWholeNumber("0", 1, 100));
  EXPECT_FALSE(parseWholeNumber("101", 1, 100));
  EXPECT_FALSE(parseWholeNumber("99999999999999999999999", LONG_MIN, LONG_MAX));
}

TEST(NumberText, ImageSizesWidthByHeight) {
  EXPECT_EQ(parseImageSize("640x480"), std::make_pair(640, 480));
  EXPECT_EQ(parseImageSize("480x640"), std::make_pair(480, 640));
  for (const char* bad : {"640", "640x", "x480", "640x480x3", "640X480", "0x480", "640x-1",
                          "640x480junk", " 640x480", "1e3x480"})
    EXPECT_FALSE(parseImageSize(bad)) << bad;
}

TEST(NumberText, FiniteRealNumbers) {
  EXPECT_DOUBLE_EQ(*parseRealNumber("0.25"), 0.25);
  EXPECT_DOUBLE_EQ(*parseRealNumber("-1e-3"), -1e-3);
  EXPECT_DOUBLE_EQ(*parseRealNumber("7"), 7.0);
  for (const char* bad : {"", "0.01xyz", "nan", "inf", "-inf", "1e999", " 1", "1 ", "."})
    EXPECT_FALSE(parseRealNumber(bad)) << "'" << bad << "'";
}

}  // namespace
}  // namespace ply_slam
