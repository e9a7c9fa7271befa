#include "deformable_sim/bench/heap_usage.h"

#include <malloc.h>

namespace deformable_sim::bench {

std::size_t liveHeapBytes() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

}  // namespace deformable_sim::bench
