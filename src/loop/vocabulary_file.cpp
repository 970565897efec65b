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
#include "ply_slam/loop/fnv1a.h"

namespace ply_slam {

namespace {

constexpr char kMagic[8] = {'P', 'L', 'Y', 'V', 'O', 'C', 'A', 'B'};
constexpr size_t kHeaderBytes = 8 + 7 * 4;

struct Header {
  uint32_t version, kind, branching, levels, bits, nodes, words;
};

void putU32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void putU64(std::vector<uint8_t>& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
uint32_t getU32(const uint8_t* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(p[i]) << (8 * i);
  return v;
}
uint64_t getU64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("vocabulary file " + path + ": " + what);
}

std::vector<uint8_t> encode(const VocabularyData& data) {
  std::vector<uint8_t> out(kMagic, kMagic + sizeof(kMagic));
  for (uint32_t v :
       {VocabularyFile::kVersion, static_cast<uint32_t>(data.kind),
        static_cast<uint32_t>(data.branching), static_cast<uint32_t>(data.levels),
        static_cast<uint32_t>(data.descriptor_bytes * 8), static_cast<uint32_t>(data.numNodes()),
        static_cast<uint32_t>(data.idf.size())})
    putU32(out, v);
  for (uint32_t parent : data.parents) putU32(out, parent);
  out.insert(out.end(), data.centres.begin(), data.centres.end());
  for (double idf : data.idf) {
    uint64_t bits;
    std::memcpy(&bits, &idf, sizeof bits);
    putU64(out, bits);
  }
  putU64(out, fnv1a64(out.data(), out.size()));
  return out;
}

std::vector<uint8_t> readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot be opened (missing or unreadable)");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  if (in.bad()) fail(path, "read error");
  return bytes;
}

Header readHeader(const std::string& path, const std::vector<uint8_t>& bytes) {
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0)
    fail(path, bytes.size() < sizeof(kMagic) ? "truncated (no header)"
                                             : "bad magic: not a ply_slam vocabulary");
  if (bytes.size() < kHeaderBytes) fail(path, "truncated (header incomplete)");
  const uint8_t* p = bytes.data() + sizeof(kMagic);
  Header h{getU32(p),      getU32(p + 4),  getU32(p + 8), getU32(p + 12),
           getU32(p + 16), getU32(p + 20), getU32(p + 24)};
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
  data.parents.resize(h.nodes);
  for (uint32_t i = 0; i < h.nodes; ++i, p += 4) data.parents[i] = getU32(p);
  data.centres.assign(p, p + size_t{h.nodes} * data.descriptor_bytes);
  p += data.centres.size();
  data.idf.resize(h.words);
  for (uint32_t i = 0; i < h.words; ++i, p += 8) {
    const uint64_t bits = getU64(p);
    std::memcpy(&data.idf[i], &bits, sizeof bits);
  }
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

VocabularyData VocabularyFile::read(const std::string& path, DescriptorKind expected_kind) {
  const std::vector<uint8_t> bytes = readAll(path);
  const Header h = readHeader(path, bytes);
  const uint64_t size = expectedSize(h);
  if (bytes.size() < size)
    fail(path, "truncated: " + std::to_string(bytes.size()) + " bytes, the header announces " +
                   std::to_string(size));
  if (bytes.size() > size) fail(path, "trailing bytes after the checksum");
  if (fnv1a64(bytes.data(), size - 8) != getU64(bytes.data() + size - 8))
    fail(path, "checksum mismatch (corrupted)");
  if (h.kind > 1) fail(path, "unknown descriptor kind " + std::to_string(h.kind));
  const DescriptorKind kind = static_cast<DescriptorKind>(h.kind);
  if (kind != expected_kind)
    fail(path, "wrong kind: holds " + descriptorKindName(kind) + " words, expected " +
                   descriptorKindName(expected_kind));
  return decode(path, h, bytes.data() + kHeaderBytes);
}

}  // namespace ply_slam
