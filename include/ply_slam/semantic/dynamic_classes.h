#pragma once

#include <string>

namespace ply_slam {

// Classes that move by themselves (PAPER.md §3.2, "active dynamic": people, animals,
// vehicles), by COCO name. Features on their instances are never used as static.
bool isActiveDynamicClass(const std::string& class_name);

}  // namespace ply_slam
