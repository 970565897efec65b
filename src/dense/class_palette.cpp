#include "ply_slam/dense/class_palette.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/input_file.h"

namespace ply_slam {
namespace {

// COCO's 80 class names, in the order of the YOLO models' coco.names.
const char* const kCocoNames[] = {"person",        "bicycle",      "car",
                                  "motorcycle",    "airplane",     "bus",
                                  "train",         "truck",        "boat",
                                  "traffic light", "fire hydrant", "stop sign",
                                  "parking meter", "bench",        "bird",
                                  "cat",           "dog",          "horse",
                                  "sheep",         "cow",          "elephant",
                                  "bear",          "zebra",        "giraffe",
                                  "backpack",      "umbrella",     "handbag",
                                  "tie",           "suitcase",     "frisbee",
                                  "skis",          "snowboard",    "sports ball",
                                  "kite",          "baseball bat", "baseball glove",
                                  "skateboard",    "surfboard",    "tennis racket",
                                  "bottle",        "wine glass",   "cup",
                                  "fork",          "knife",        "spoon",
                                  "bowl",          "banana",       "apple",
                                  "sandwich",      "orange",       "broccoli",
                                  "carrot",        "hot dog",      "pizza",
                                  "donut",         "cake",         "chair",
                                  "couch",         "potted plant", "bed",
                                  "dining table",  "toilet",       "tv",
                                  "laptop",        "mouse",        "remote",
                                  "keyboard",      "cell phone",   "microwave",
                                  "oven",          "toaster",      "sink",
                                  "refrigerator",  "book",         "clock",
                                  "vase",          "scissors",     "teddy bear",
                                  "hair drier",    "toothbrush"};

// HSV (h in [0, 360), s and v in [0, 1]) to 8-bit RGB.
ClassColour fromHsv(double h, double s, double v) {
  const double c = v * s;
  const double x = c * (1.0 - std::abs(std::fmod(h / 60.0, 2.0) - 1.0));
  const double m = v - c;
  double r = 0, g = 0, b = 0;
  if (h < 60) {
    r = c, g = x;
  } else if (h < 120) {
    r = x, g = c;
  } else if (h < 180) {
    g = c, b = x;
  } else if (h < 240) {
    g = x, b = c;
  } else if (h < 300) {
    r = x, b = c;
  } else {
    r = c, b = x;
  }
  auto byte = [m](double value) {
    return static_cast<std::uint8_t>(std::lround(255 * (value + m)));
  };
  return {byte(r), byte(g), byte(b)};
}

}  // namespace

ClassPalette::ClassPalette() {
  names_.push_back("unknown");
  colours_.push_back({170, 170, 170});  // grey: walls, floor, whatever has no instance
  for (const char* name : kCocoNames) names_.push_back(name);
  // Golden-angle hues spread neighbouring labels apart; saturation and value cycle so that
  // labels of similar hue still differ. Person (label 1) is the red people expect.
  for (size_t label = 1; label < names_.size(); ++label) {
    const double hue = std::fmod(350.0 + 137.508 * (label - 1), 360.0);
    const double saturation = 0.85 - 0.2 * ((label - 1) % 3) / 2.0;
    const double value = 0.95 - 0.25 * ((label - 1) / 3 % 2);
    colours_.push_back(fromHsv(hue, saturation, value));
  }
}

ClassPalette ClassPalette::fromFile(const std::string& path) {
  if (const auto problem = specialFileProblem(path))
    throw std::runtime_error("palette " + path + ": " + *problem);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("palette " + path + ": cannot open the file");
  ClassPalette palette;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    int r = -1, g = -1, b = -1;
    std::string name, word;
    fields >> r >> g >> b;
    while (fields >> word) name += (name.empty() ? "" : " ") + word;
    const auto where = "palette " + path + " line " + std::to_string(number) + ": ";
    if (fields.bad() || r < 0 || r > 255 || g < 0 || g > 255 || b < 0 || b > 255 || name.empty())
      throw std::runtime_error(where + "expected 'r g b class name' with r g b in 0..255");
    const std::uint32_t label = palette.label(name);
    if (label == kUnknown && name != "unknown")
      throw std::runtime_error(where + "'" + name + "' is not a COCO class (nor unknown)");
    palette.colours_[label] = {static_cast<std::uint8_t>(r), static_cast<std::uint8_t>(g),
                               static_cast<std::uint8_t>(b)};
  }
  return palette;
}

const std::string& ClassPalette::name(std::uint32_t label) const {
  return label < names_.size() ? names_[label] : names_[kUnknown];
}

ClassColour ClassPalette::colour(std::uint32_t label) const {
  return label < colours_.size() ? colours_[label] : colours_[kUnknown];
}

std::uint32_t ClassPalette::label(const std::string& class_name) const {
  for (size_t i = 1; i < names_.size(); ++i)
    if (names_[i] == class_name) return static_cast<std::uint32_t>(i);
  return kUnknown;
}

void ClassPalette::writeLegend(const std::string& path,
                               const std::vector<std::uint32_t>& labels) const {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# ply_slam map legend: label r g b class name\n"
         "# label = the 'label' field of dense_map.pcd/.ply; r g b = the colour of the class in\n"
         "# semantic_octree.ot and map_top.png\n";
  std::vector<std::uint32_t> shown = labels;
  if (shown.empty())
    for (std::uint32_t l = 0; l < names_.size(); ++l) shown.push_back(l);
  for (const std::uint32_t l : shown) {
    const ClassColour c = colour(l);
    out << l << ' ' << int(c.r) << ' ' << int(c.g) << ' ' << int(c.b) << ' ' << name(l) << '\n';
  }
  file.commit();
}

}  // namespace ply_slam
