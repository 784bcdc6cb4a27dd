// Integer voxel coordinates (and a fourth slot, e.g. a time slot) to dense cell indices: an
// open-addressing hash table whose cells are numbered in order of their first key, so what is
// built from it is deterministic for a given input order. Shared by the scan downsampling and
// the local map's merge, where std::unordered_map's node per voxel cost more than the rest.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tacs {

/// Linear probing over slots that hold the key itself (a probe reads one slot, not the slot and
/// then a key elsewhere). `Traits` gives the key type, its hash and its equality.
template <class Traits>
class OpenAddressingIndex {
 public:
  using Key = typename Traits::Key;

  /// Sized for about `expected` distinct keys (it grows past them).
  explicit OpenAddressingIndex(size_t expected) { reset(expected); }

  /// The key's cell; a new key is given `next` and `next` is returned.
  uint32_t insert(const Key& key, uint32_t next) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    size_t h = Traits::hash(key) & mask_;
    while (slots_[h].cell != kEmpty && !Traits::same(slots_[h].key, key)) h = (h + 1) & mask_;
    if (slots_[h].cell == kEmpty) {
      slots_[h] = {key, next};
      ++size_;
    }
    return slots_[h].cell;
  }
  /// The key's cell, numbering new keys 0, 1, 2, ... in order of their first insert.
  size_t insert(const Key& key) { return insert(key, static_cast<uint32_t>(size_)); }

  size_t size() const { return size_; }

 private:
  static constexpr uint32_t kEmpty = ~uint32_t{0};
  struct Slot {
    Key key{};
    uint32_t cell = kEmpty;
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
      if (s.cell == kEmpty) continue;
      size_t h = Traits::hash(s.key) & mask_;
      while (slots_[h].cell != kEmpty) h = (h + 1) & mask_;
      slots_[h] = s;
    }
    size_ = n;
  }

  std::vector<Slot> slots_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

/// Any 64-bit voxel coordinates and fourth slot.
struct VoxelKeyTraits {
  using Key = std::array<int64_t, 4>;
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
};
using VoxelIndex = OpenAddressingIndex<VoxelKeyTraits>;

/// Voxel keys packed into one 64-bit word (pack()): each coordinate in 20 bits (+-524288
/// voxels, +-52 km at 0.1 m), the fourth slot in 4. A slot of the table is 16 bytes where
/// VoxelIndex's is 40: on a dense scan in arbitrary point order each insert is a cache miss, and
/// a smaller table takes fewer of them.
struct PackedVoxelKeyTraits {
  using Key = uint64_t;
  static constexpr int64_t kAxisLimit = int64_t{1} << 19;
  static constexpr int64_t kSlotLimit = 16;

  /// Packs the key into *packed when it fits, else returns false.
  static bool pack(const VoxelKeyTraits::Key& key, uint64_t* packed) {
    for (int d = 0; d < 3; ++d) {
      if (key[d] < -kAxisLimit || key[d] >= kAxisLimit) return false;
    }
    if (key[3] < 0 || key[3] >= kSlotLimit) return false;
    *packed = static_cast<uint64_t>(key[0] + kAxisLimit) |
              static_cast<uint64_t>(key[1] + kAxisLimit) << 20 |
              static_cast<uint64_t>(key[2] + kAxisLimit) << 40 |
              static_cast<uint64_t>(key[3]) << 60;
    return true;
  }
  static bool same(uint64_t a, uint64_t b) { return a == b; }
  static size_t hash(uint64_t k) {  // MurmurHash3's 64-bit finaliser
    k ^= k >> 33;
    k *= 0xFF51AFD7ED558CCDull;
    k ^= k >> 33;
    k *= 0xC4CEB9FE1A85EC53ull;
    k ^= k >> 33;
    return static_cast<size_t>(k);
  }
};
using PackedVoxelIndex = OpenAddressingIndex<PackedVoxelKeyTraits>;

}  // namespace tacs
