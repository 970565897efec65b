#pragma once

#include <string>

#include "ply_slam/dense/key_frame_cloud.h"

namespace ply_slam {

// The dense cloud as binary PCD and PLY files, whole or absent (AtomicFile). PCL's writers
// do not do for a full disk: the PLY writer never checks its stream (a 45 kB dense_map.ply
// whose header announced 7 262 points, issue #53), and the PCD writer fills an mmap, which a
// full disk answers with SIGBUS where fallocate is not supported. Each throws a FileWriteError
// naming the file.
void writeCloudPcd(const std::string& path, const DenseCloud& cloud);
void writeCloudPly(const std::string& path, const DenseCloud& cloud);

}  // namespace ply_slam
