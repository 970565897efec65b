#include "ply_slam/semantic/onnx_input_shape.h"

#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>

#include "ply_slam/io/input_file.h"

namespace ply_slam {
namespace {

// Field numbers of the ONNX protobuf messages on the way to the input shape (onnx.proto).
constexpr int kModelGraph = 7;     // ModelProto.graph
constexpr int kGraphInput = 11;    // GraphProto.input
constexpr int kValueInfoType = 2;  // ValueInfoProto.type
constexpr int kTypeTensor = 1;     // TypeProto.tensor_type
constexpr int kTensorShape = 2;    // TypeProto.Tensor.shape
constexpr int kShapeDim = 1;       // TensorShapeProto.dim
constexpr int kDimValue = 1;       // TensorShapeProto.Dimension.dim_value

// A view of protobuf bytes, read field by field.
class ProtoReader {
 public:
  ProtoReader(const char* begin, const char* end) : p_(begin), end_(end) {}

  struct Field {
    int number = 0;
    int wire_type = 0;
    std::uint64_t value = 0;      // varint fields
    const char* begin = nullptr;  // length-delimited fields
    const char* end = nullptr;
  };

  // The next field, or nothing at the end; throws on bytes that are no protobuf.
  std::optional<Field> next() {
    if (p_ >= end_) return std::nullopt;
    Field f;
    const std::uint64_t key = varint();
    f.number = static_cast<int>(key >> 3);
    f.wire_type = static_cast<int>(key & 7);
    switch (f.wire_type) {
      case 0:
        f.value = varint();
        break;
      case 1:
        skip(8);
        break;
      case 2: {
        const std::uint64_t length = varint();
        if (length > static_cast<std::uint64_t>(end_ - p_)) throw std::runtime_error("truncated");
        f.begin = p_;
        f.end = p_ + length;
        p_ += length;
        break;
      }
      case 5:
        skip(4);
        break;
      default:
        throw std::runtime_error("unknown wire type");
    }
    return f;
  }

 private:
  std::uint64_t varint() {
    std::uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (p_ >= end_) throw std::runtime_error("truncated");
      const auto byte = static_cast<unsigned char>(*p_++);
      value |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
      if (!(byte & 0x80)) return value;
    }
    throw std::runtime_error("bad varint");
  }
  void skip(std::ptrdiff_t n) {
    if (end_ - p_ < n) throw std::runtime_error("truncated");
    p_ += n;
  }

  const char* p_;
  const char* end_;
};

// The bytes of the first length-delimited field `number` inside [begin, end).
std::optional<std::pair<const char*, const char*>> fieldBytes(const char* begin, const char* end,
                                                              int number) {
  ProtoReader reader(begin, end);
  while (const auto f = reader.next())
    if (f->number == number && f->wire_type == 2) return std::make_pair(f->begin, f->end);
  return std::nullopt;
}

std::vector<std::int64_t> shapeOf(const char* begin, const char* end) {
  std::vector<std::int64_t> dims;
  ProtoReader shape(begin, end);
  while (const auto dim = shape.next()) {
    if (dim->number != kShapeDim || dim->wire_type != 2) continue;
    std::int64_t value = -1;  // a named (dynamic) dimension
    ProtoReader fields(dim->begin, dim->end);
    while (const auto f = fields.next())
      if (f->number == kDimValue && f->wire_type == 0 && static_cast<std::int64_t>(f->value) > 0)
        value = static_cast<std::int64_t>(f->value);
    dims.push_back(value);
  }
  return dims;
}

std::vector<std::int64_t> inputShape(const std::string& bytes) {
  const char* begin = bytes.data();
  const char* end = begin + bytes.size();
  auto range = fieldBytes(begin, end, kModelGraph);
  if (!range) return {};
  for (const int number : {kGraphInput, kValueInfoType, kTypeTensor, kTensorShape}) {
    range = fieldBytes(range->first, range->second, number);
    if (!range) return {};
  }
  return shapeOf(range->first, range->second);
}

}  // namespace

std::string readOnnxModelFile(const std::string& path) {
  refuseSpecialFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read the ONNX model");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(path + ": read error in the ONNX model");
  return bytes;
}

std::vector<std::int64_t> onnxInputShape(const std::string& bytes, const std::string& path) {
  try {
    return inputShape(bytes);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": not an ONNX model (" + e.what() + ")");
  }
}

}  // namespace ply_slam
