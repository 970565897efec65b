#include "ply_slam/io/byte_reader.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "ply_slam/io/input_file.h"

namespace ply_slam {

uint64_t ByteReader::word(const uint8_t* p, int size) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

const uint8_t* ByteReader::take(size_t size) {
  if (size > remaining())
    throw Truncated("needs " + std::to_string(size) + " bytes at offset " +
                    std::to_string(offset_) + ", " + std::to_string(remaining()) + " left");
  const uint8_t* p = data_ + offset_;
  offset_ += size;
  return p;
}

float ByteReader::f32() {
  const uint32_t bits = u32();
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

double ByteReader::f64() {
  const uint64_t bits = u64();
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

std::string ByteReader::text() {
  const uint32_t size = u32();
  const uint8_t* p = take(size);
  return std::string(reinterpret_cast<const char*>(p), size);
}

std::optional<std::vector<uint8_t>> readFileBytes(const std::string& path, std::string* why) {
  auto none = [why](const std::string& reason) {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (const auto problem = specialFileProblem(path)) return none(*problem);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return none(errno == ENOENT ? "cannot be opened (missing)"
                                : std::string("cannot be opened: ") + std::strerror(errno));
  try {
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    if (in.bad()) return none("read error");
    return bytes;
  } catch (const std::exception& e) {  // libstdc++ throws from underflow on a read error
    return none(std::string("read error: ") + e.what());
  }
}

}  // namespace ply_slam
