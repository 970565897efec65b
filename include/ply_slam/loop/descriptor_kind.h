#pragma once

#include <optional>
#include <string>

namespace ply_slam {

// Which binary descriptor a vocabulary was trained on: ORB points and LBD lines share the
// 256-bit layout, so only this tag keeps one from being used for the other.
enum class DescriptorKind { kOrb = 0, kLbd = 1 };

std::string descriptorKindName(DescriptorKind kind);  // "orb" or "lbd"
std::optional<DescriptorKind> parseDescriptorKind(const std::string& name);

}  // namespace ply_slam
