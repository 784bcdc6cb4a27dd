#include "tacs_graphs/common/heap.h"

#include <cstdlib>  // defines __GLIBC__ when the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tacs {

void retainFreedHeapMemory() {
#if defined(__GLIBC__)
  // 32 MB is glibc's ceiling for the mmap threshold on 64-bit; blocks above it (a map export's
  // buffers) still go straight to the kernel and back.
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
#endif
}

}  // namespace tacs
