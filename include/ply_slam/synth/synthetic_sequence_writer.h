#pragma once

#include <functional>
#include <string>

#include "ply_slam/synth/synthetic_sequence.h"

namespace ply_slam {

struct SynthWriteStats {
  int frames = 0;
  double render_ms = 0.0;  // total, rendering and sensor noise
  double write_ms = 0.0;   // total, PNG encoding and file output
};

// Writes a sequence as a TUM RGB-D folder: rgb/ depth/ (16-bit, metres x 5000) masks/
// (8-bit instance ids), rgb.txt depth.txt associations.txt groundtruth.txt, plus
// instances.txt ("id class"), lines.txt ("x1 y1 z1 x2 y2 z2", world frame) and camera.yaml
// (loadConfig). Creates the folder; throws std::runtime_error naming the path it cannot write.
// progress(i) is called after frame i when given.
SynthWriteStats writeSyntheticSequence(const SyntheticSequence& sequence, const std::string& dir,
                                       const std::function<void(int)>& progress = nullptr);

// The camera section alone, as camera.yaml holds it.
std::string cameraYaml(const PinholeCamera& camera, const std::string& comment);

}  // namespace ply_slam
