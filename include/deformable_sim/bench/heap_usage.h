// How much heap memory the process holds, to charge each setting with the memory its body and
// solver keep (a difference of two readings), without instrumenting the core.
#pragma once

#include <cstddef>

namespace deformable_sim::bench {

/// Bytes in use on the heap now: glibc's allocated chunks in every arena plus mmapped blocks
/// (mallinfo2). Freed memory does not count, whether or not it went back to the system.
std::size_t liveHeapBytes();

}  // namespace deformable_sim::bench
