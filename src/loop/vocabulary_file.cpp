#include "ply_slam/loop/vocabulary_file.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/byte_reader.h"
#include "ply_slam/io/byte_writer.h"
#include "ply_slam/io/fnv1a.h"

namespace ply_slam {

namespace {

constexpr char kMagic[8] = {'P', 'L', 'Y', 'V', 'O', 'C', 'A', 'B'};
constexpr size_t kHeaderBytes = 8 + 7 * 4;

struct Header {
  uint32_t version, kind, branching, levels, bits, nodes, words;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("vocabulary file " + path + ": " + what);
}

std::vector<uint8_t> encode(const VocabularyData& data) {
  ByteWriter out;
  out.raw(reinterpret_cast<const uint8_t*>(kMagic), sizeof(kMagic));
  for (uint32_t v :
       {VocabularyFile::kVersion, static_cast<uint32_t>(data.kind),
        static_cast<uint32_t>(data.branching), static_cast<uint32_t>(data.levels),
        static_cast<uint32_t>(data.descriptor_bytes * 8), static_cast<uint32_t>(data.numNodes()),
        static_cast<uint32_t>(data.idf.size())})
    out.u32(v);
  for (uint32_t parent : data.parents) out.u32(parent);
  out.raw(data.centres.data(), data.centres.size());
  for (double idf : data.idf) out.f64(idf);
  out.u64(fnv1a64(out.bytes().data(), out.bytes().size()));
  return std::move(out.bytes());
}

std::vector<uint8_t> readAll(const std::string& path) {
  std::string why;
  std::optional<std::vector<uint8_t>> bytes = readFileBytes(path, &why);
  if (!bytes) fail(path, why);
  return std::move(*bytes);
}

Header readHeader(const std::string& path, const std::vector<uint8_t>& bytes) {
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail(path, bytes.size() < sizeof(kMagic) ? "truncated (no header)"
                                             : "bad magic: not a ply_slam vocabulary");
  if (bytes.size() < kHeaderBytes) fail(path, "truncated (header incomplete)");
  ByteReader in(bytes.data() + sizeof(kMagic), kHeaderBytes - sizeof(kMagic));
  Header h{in.u32(), in.u32(), in.u32(), in.u32(), in.u32(), in.u32(), in.u32()};
  if (h.version != VocabularyFile::kVersion)
    fail(path, "format version " + std::to_string(h.version) + ", this build reads " +
                   std::to_string(VocabularyFile::kVersion));
  if (h.bits == 0 || h.bits % 8 != 0 || h.bits > 8 * 1024)
    fail(path, "bad descriptor size " + std::to_string(h.bits) + " bits");
  return h;
}

uint64_t expectedSize(const Header& h) {
  return kHeaderBytes + uint64_t{h.nodes} * (4 + h.bits / 8) + uint64_t{h.words} * 8 + 8;
}

VocabularyData decode(const std::string& path, const Header& h, const uint8_t* p) {
  VocabularyData data;
  data.kind = static_cast<DescriptorKind>(h.kind);
  data.branching = static_cast<int>(h.branching);
  data.levels = static_cast<int>(h.levels);
  data.descriptor_bytes = static_cast<int>(h.bits / 8);
  ByteReader in(p, expectedSize(h) - kHeaderBytes);
  data.parents.resize(h.nodes);
  for (uint32_t i = 0; i < h.nodes; ++i) data.parents[i] = in.u32();
  const size_t centre_bytes = size_t{h.nodes} * data.descriptor_bytes;
  const uint8_t* centres = in.raw(centre_bytes);
  data.centres.assign(centres, centres + centre_bytes);
  data.idf.resize(h.words);
  for (uint32_t i = 0; i < h.words; ++i) data.idf[i] = in.f64();
  if (h.nodes == 0 || data.parents[0] != VocabularyData::kNoParent)
    fail(path, "inconsistent tree (no root)");
  std::vector<bool> has_children(h.nodes, false);
  for (uint32_t i = 1; i < h.nodes; ++i) {
    if (data.parents[i] >= i) fail(path, "inconsistent tree (node " + std::to_string(i) + ")");
    has_children[data.parents[i]] = true;
  }
  const auto leaves = std::count(has_children.begin(), has_children.end(), false);
  if (leaves != static_cast<long>(h.words))
    fail(path, "inconsistent tree (" + std::to_string(leaves) + " leaves, " +
                   std::to_string(h.words) + " words)");
  return data;
}

}  // namespace

void VocabularyFile::write(const std::string& path, const VocabularyData& data) {
  const std::vector<uint8_t> bytes = encode(data);
  AtomicFile file(path, std::ios::binary);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

uint64_t VocabularyFile::checksum(const VocabularyData& data) {
  const std::vector<uint8_t> bytes = encode(data);
  return ByteReader::word(bytes.data() + bytes.size() - 8, 8);
}

VocabularyData VocabularyFile::read(const std::string& path, DescriptorKind expected_kind) {
  const std::vector<uint8_t> bytes = readAll(path);
  const Header h = readHeader(path, bytes);
  const uint64_t size = expectedSize(h);
  if (bytes.size() < size)
    fail(path, "truncated: " + std::to_string(bytes.size()) + " bytes, the header announces " +
                   std::to_string(size));
  if (bytes.size() > size) fail(path, "trailing bytes after the checksum");
  if (fnv1a64(bytes.data(), size - 8) != ByteReader::word(bytes.data() + size - 8, 8))
    fail(path, "checksum mismatch (corrupted)");
  if (h.kind > 1) fail(path, "unknown descriptor kind " + std::to_string(h.kind));
  const DescriptorKind kind = static_cast<DescriptorKind>(h.kind);
  if (kind != expected_kind)
    fail(path, "wrong kind: holds " + descriptorKindName(kind) + " words, expected " +
                   descriptorKindName(expected_kind));
  return decode(path, h, bytes.data() + kHeaderBytes);
}

}  // namespace ply_slam
