#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ply_slam {

// An ONNX model file's bytes, read once: OpenCV DNN loads the net from them
// (cv::dnn::readNetFromONNX(buffer, size)) and onnxInputShape reads them. Throws
// std::runtime_error naming a file it cannot read (a FIFO or a directory is refused).
std::string readOnnxModelFile(const std::string& path);

// The dimensions of an ONNX model's first graph input (e.g. {1, 3, 480, 640} for a YOLOv8
// export of height 480 and width 640), read straight from the protobuf bytes: OpenCV DNN runs
// a fixed-size export on an input of the same area but transposed sides without a word, with
// anchors and masks then silently wrong. A dimension without a fixed value is -1; empty when
// the model holds no input shape. Throws std::runtime_error naming `path` for bytes that are
// no protobuf.
std::vector<std::int64_t> onnxInputShape(const std::string& bytes, const std::string& path);

}  // namespace ply_slam
