#pragma once

namespace ply_slam {

// How a background thread shares the CPU with tracking (docs/RESULTS.md, "Live through both
// nodes"): on 2 cores the segmentation network and the dense maps would otherwise take their
// equal share of every core the tracker needs, and frames wait. At nice +10 a thread gets ~1/10
// of a core it contends for with one at 0 (the kernel's weights 110 : 1024), and all of an idle
// one.
constexpr int kBackgroundNice = 10;

// Sets the calling thread's nice value (Linux keeps one per thread; raising one's own needs no
// privilege). Best effort: false when the system refused.
bool setThisThreadsNice(int nice);

}  // namespace ply_slam
