#include "ply_slam/io/byte_writer.h"

#include <cstring>

namespace ply_slam {

void ByteWriter::f32(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  u32(bits);
}

void ByteWriter::f64(double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  u64(bits);
}

void ByteWriter::text(const std::string& s) {
  u32(static_cast<uint32_t>(s.size()));
  raw(reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

}  // namespace ply_slam
