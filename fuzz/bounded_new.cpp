// A cap on single allocations for the fuzzers. ros::serialization resizes a vector or string
// to the length the bytes declare before it reads the elements, so 4 bytes can ask for 4 GB;
// ASan would report that as a fatal out-of-memory and stop the run. Over the cap, new throws
// std::bad_alloc instead, which the harnesses count as bytes no subscriber would receive.
// (Real images are far below it: 640x480 float depth is 1.2 MB.)
#include <cstdlib>
#include <new>

namespace {
constexpr size_t kMaxAllocation = size_t{64} << 20;
}

void* operator new(size_t size) {
  void* p = size <= kMaxAllocation ? std::malloc(size ? size : 1) : nullptr;
  if (!p) throw std::bad_alloc();
  return p;
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

// Memory allocated by ASan's own operator new (new[], code in shared libraries) may come back
// through the delete above, which frees it with free(): the same allocator, not a bug.
extern "C" const char* __asan_default_options() { return "alloc_dealloc_mismatch=0"; }
