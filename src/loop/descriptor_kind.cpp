#include "ply_slam/loop/descriptor_kind.h"

namespace ply_slam {

std::string descriptorKindName(DescriptorKind kind) {
  return kind == DescriptorKind::kLbd ? "lbd" : "orb";
}

std::optional<DescriptorKind> parseDescriptorKind(const std::string& name) {
  if (name == "orb") return DescriptorKind::kOrb;
  if (name == "lbd") return DescriptorKind::kLbd;
  return std::nullopt;
}

}  // namespace ply_slam
