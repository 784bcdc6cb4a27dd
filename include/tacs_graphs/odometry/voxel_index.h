// Integer voxel coordinates (and a fourth slot, e.g. a time slot) to dense cell indices: an
// open-addressing hash table whose cells are numbered in order of their first key, so what is
// built from it is deterministic for a given input order. Shared by the scan downsampling and
// the local map's merge, where std::unordered_map's node per voxel cost more than the rest.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tacs {

class VoxelIndex {
 public:
  using Key = std::array<int64_t, 4>;

  /// Sized for about `expected` distinct keys (it grows past them).
  explicit VoxelIndex(size_t expected) { reset(expected); }

  /// The key's cell index: size() before the call when the key is new.
  size_t insert(const Key& key) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    size_t h = hash(key) & mask_;
    // The key sits in its slot: a probe reads one slot, not the slot and then a key elsewhere.
    while (slots_[h].cell >= 0 && !same(slots_[h].key, key)) h = (h + 1) & mask_;
    if (slots_[h].cell < 0) slots_[h] = {key, static_cast<int64_t>(size_++)};
    return static_cast<size_t>(slots_[h].cell);
  }

  size_t size() const { return size_; }

 private:
  struct Slot {
    Key key;
    int64_t cell = -1;
  };

  void reset(size_t expected) {
    size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    slots_.assign(capacity, Slot());
    mask_ = capacity - 1;
    size_ = 0;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    const size_t n = size_;
    reset(2 * n + 8);
    for (const Slot& s : old) {
      if (s.cell < 0) continue;
      size_t h = hash(s.key) & mask_;
      while (slots_[h].cell >= 0) h = (h + 1) & mask_;
      slots_[h] = s;
    }
    size_ = n;
  }
  // Spelled out: std::array's == became a memcmp call, a few percent of a dense scan's odometry.
  static bool same(const Key& a, const Key& b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && a[3] == b[3];
  }
  static size_t hash(const Key& k) {
    uint64_t h = static_cast<uint64_t>(k[0]) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(k[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(k[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(k[3]) * 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h ^ (h >> 29));
  }

  std::vector<Slot> slots_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

}  // namespace tacs
