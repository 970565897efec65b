#pragma once

#include <optional>
#include <string>
#include <utility>

namespace ply_slam {

// Numbers typed by a user (command-line options): the whole text must be the number, so
// "12x", "1e3" for a count, " 5" or "" are refused rather than read as far as they go.
// A whole number in [min, max], or nothing.
std::optional<long> parseWholeNumber(const std::string& text, long min, long max);
// A finite decimal number (strtod syntax), or nothing.
std::optional<double> parseRealNumber(const std::string& text);
// An image size "WxH" (e.g. "640x480"), each side in [1, 100000]: (width, height), or nothing.
std::optional<std::pair<int, int>> parseImageSize(const std::string& text);
// The shortest text that reads back as exactly `value` ("517.3", "517.30000000000001"): two
// numbers that differ never print the same.
std::string exactText(double value);

}  // namespace ply_slam
