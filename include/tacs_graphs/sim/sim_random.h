// Counter-based random numbers for the simulator: every ray draws from a generator seeded by
// (seed, scan, ray), so results do not depend on evaluation order and are identical across runs
// (std::normal_distribution is implementation-defined, hence our own Box-Muller).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace tacs::sim {

inline uint64_t splitMix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

inline uint64_t mixSeed(uint64_t a, uint64_t b) { return splitMix64(a ^ splitMix64(b)); }

class SplitMix {
 public:
  explicit SplitMix(uint64_t state) : state_(state) {}
  /// Uniform in [0, 1).
  double uniform() {
    state_ = splitMix64(state_);
    return static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }
  /// Two independent standard normals (both outputs of one Box-Muller draw).
  void gaussianPair(double* a, double* b) {
    const double r = std::sqrt(-2.0 * std::log(1.0 - uniform()));  // 1 - u in (0, 1]
    const double phi = 6.283185307179586 * uniform();
    *a = r * std::cos(phi);
    *b = r * std::sin(phi);
  }

 private:
  uint64_t state_;
};

/// 65536 standard-normal samples (fixed, seed-independent): a ray looks its noise up with 16
/// bits of its own hash, which is several times cheaper than Box-Muller per ray.
inline const std::array<float, 65536>& gaussianTable() {
  static const std::array<float, 65536> table = [] {
    std::array<float, 65536> t{};
    SplitMix rng(0x6761757373ULL);  // "gauss"
    for (size_t i = 0; i < t.size(); i += 2) {
      double a, b;
      rng.gaussianPair(&a, &b);
      t[i] = static_cast<float>(a), t[i + 1] = static_cast<float>(b);
    }
    return t;
  }();
  return table;
}

/// Three draws from one 64-bit hash: a uniform in [0, 1) and two standard normals.
struct RayNoise {
  double uniform, gauss_a, gauss_b;
  explicit RayNoise(uint64_t hash) {
    const auto& g = gaussianTable();
    uniform = static_cast<double>(hash >> 40) * 0x1.0p-24;
    gauss_a = g[(hash >> 16) & 0xFFFF];
    gauss_b = g[hash & 0xFFFF];
  }
};

}  // namespace tacs::sim
