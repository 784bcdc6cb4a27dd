// Keeping freed heap memory for reuse: every scan allocates and frees clouds, voxel tables and
// KD-trees of the same few megabytes. glibc by default hands large blocks back to the kernel
// (mmap'd blocks above the mmap threshold, and the heap's top above the trim threshold), so the
// next scan page-faults all of it in again: 3-5 % of an offline run's samples were page faults.
#pragma once

namespace tacs {

/// Raises glibc's mmap and trim thresholds so the freed blocks stay in the process for the next
/// scan (offline runs 5-50 % more scans/s on the worlds). Call once at the start of main(); a no-op
/// on other C libraries. The process keeps its peak heap instead of shrinking after it.
void retainFreedHeapMemory();

}  // namespace tacs
