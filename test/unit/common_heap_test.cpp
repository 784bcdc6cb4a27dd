#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "tacs_graphs/common/heap.h"

#if defined(__GLIBC__)
#include <malloc.h>

namespace tacs {
namespace {

// A scan-sized block (16 MB) is taken from the heap, not mapped for itself, and stays in the
// process once freed, ready for the next scan.
TEST(RetainFreedHeapMemory, AScanSizedBlockIsKeptForReuseAfterItIsFreed) {
  retainFreedHeapMemory();
  constexpr size_t kBlock = 16u << 20;
  const size_t mapped_before = mallinfo2().hblkhd;
  {
    std::vector<char> block(kBlock, 1);
    EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "the block was mapped for itself";
  }
  EXPECT_GE(mallinfo2().fordblks, kBlock) << "the freed block went back to the kernel";
}

}  // namespace
}  // namespace tacs
#endif
