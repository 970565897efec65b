// Preloaded by scripts/sanitize.sh --thread: OpenCV's parallel loops run on TBB, whose
// synchronisation (atomics in uninstrumented code) ThreadSanitizer cannot see, so every result a
// worker hands back would be reported as a race. Serial loops leave TSan our own threads.
#include <opencv2/core/utility.hpp>

namespace {
__attribute__((constructor)) void runOpenCvSerially() { cv::setNumThreads(0); }
}  // namespace
