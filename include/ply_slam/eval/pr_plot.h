#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ply_slam/eval/precision_recall.h"

namespace ply_slam {

// Writes a PNG of precision-recall curves (recall on x, precision on y, both 0..1), each named
// in the legend with its area under the curve, `title` on top. Throws std::runtime_error
// naming the file when it cannot be written.
void writePrPlot(const std::string& png_path,
                 const std::vector<std::pair<std::string, PrCurve>>& curves,
                 const std::string& title);

}  // namespace ply_slam
