#pragma once

#include <cstddef>
#include <cstdint>

namespace ply_slam {

// The map file, little-endian throughout (ByteWriter), f64/f32 as IEEE-754 bits, text as u32
// length + bytes:
//   "PLYSLMAP" | u32 version | u64 payload bytes | payload | u64 FNV-1a of every byte before it
// payload:
//   setup: f64 fx fy cx cy | u32 width height | u32 ORB levels | f64 ORB scale factor |
//          ORB vocabulary, LBD vocabulary: text file name | u64 checksum | u64 words
//   u32 keyframes, each: i64 id, frame id | f64 stamp | f64 T_cw (3 x 4, row-major) |
//          i64 parent id (-1: root) | u32 keypoints N, each: f32 x y size angle response |
//          i32 octave | f64 rectified u v | f64 undistorted u v | f32 depth; then N x 32 ORB
//          bytes | u32 line slots | u32 lines L, each: u32 slot | i64 line landmark id |
//          u32 covisible C, each: i64 keyframe id | i32 shared landmarks
//   u32 points, each: i64 id | f64 position xyz, normal xyz, min and max distance, weight |
//          32 ORB bytes | i32 visible, found | i64 first keyframe | u32 observers, each:
//          i64 keyframe id | u32 keypoint
//   u32 lines, each: i64 id | f64 start xyz, end xyz, start and end weight | 32 LBD bytes |
//          i64 first keyframe | i32 observations, found
//   u32 places, each: i64 keyframe id | u32 N flags (u8: keypoint in the place database) |
//          u32 LBD rows R, R x 32 bytes | u32 instances, each: text class | f64 x y w h
// The first keyframe is the spanning tree's root. BoW vectors are not stored: the place
// database is rebuilt at load from the descriptors with the vocabularies the setup names.
namespace map_file {

constexpr char kMagic[8] = {'P', 'L', 'Y', 'S', 'L', 'M', 'A', 'P'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderBytes = 8 + 4 + 8;
constexpr int kDescriptorBytes = 32;  // ORB and LBD

}  // namespace map_file
}  // namespace ply_slam
