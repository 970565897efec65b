#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ply_slam {

// Reads what ByteWriter wrote from a span of bytes. Reading past the end throws
// ByteReader::Truncated (the caller names the file), never reads outside the span.
class ByteReader {
 public:
  struct Truncated : std::runtime_error {
    using std::runtime_error::runtime_error;
  };

  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  uint8_t u8() { return *take(1); }
  uint32_t u32() { return static_cast<uint32_t>(get(4)); }
  uint64_t u64() { return get(8); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  int64_t i64() { return static_cast<int64_t>(u64()); }
  float f32();
  double f64();
  // `size` bytes, returned in place (valid while the span is).
  const uint8_t* raw(size_t size) { return take(size); }
  std::string text();

  size_t remaining() const { return size_ - offset_; }
  size_t offset() const { return offset_; }

  // Little-endian words at p (for fixed headers read before a reader is made).
  static uint64_t word(const uint8_t* p, int size);

 private:
  const uint8_t* take(size_t size);
  uint64_t get(int size) { return word(take(static_cast<size_t>(size)), size); }

  const uint8_t* data_;
  size_t size_;
  size_t offset_ = 0;
};

// Every byte of a file; none when it cannot be opened or read, and then `why` (when given)
// says why: missing, a directory, a named pipe (refused before opening it: it would block),
// a read error.
std::optional<std::vector<uint8_t>> readFileBytes(const std::string& path,
                                                  std::string* why = nullptr);

}  // namespace ply_slam
