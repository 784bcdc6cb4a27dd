#include "face_bottom.h"

#include <algorithm>
#include <limits>

namespace tacs::walls {

double connectedBottom(const std::vector<Eigen::Vector3f>& pts, const std::vector<uint32_t>& run,
                       const Eigen::Vector2d& axis, const Eigen::Vector3d& c, double t_min,
                       double t_max) {
  constexpr double kBand = 0.25;           // [m] height band
  constexpr double kCell = 0.5;            // [m] length cell along the face
  constexpr double kMaxVerticalGap = 1.0;  // [m]
  constexpr double kMinSpread = 0.35;      // of the cells of the most spread band
  double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo;
  for (uint32_t i : run) {
    z_lo = std::min(z_lo, static_cast<double>(pts[i].z()));
    z_hi = std::max(z_hi, static_cast<double>(pts[i].z()));
  }
  const size_t bands = static_cast<size_t>((z_hi - z_lo) / kBand) + 1;
  const size_t cells = static_cast<size_t>((t_max - t_min) / kCell) + 1;
  std::vector<uint8_t> seen(bands * cells, 0);
  for (uint32_t i : run) {
    const Eigen::Vector3d p = pts[i].cast<double>();
    const size_t band = static_cast<size_t>((p.z() - z_lo) / kBand);
    const double t = axis.dot(p.head<2>() - c.head<2>());
    const size_t cell = std::min(cells - 1, static_cast<size_t>(std::max(0.0, t - t_min) / kCell));
    seen[band * cells + cell] = 1;
  }
  std::vector<size_t> spread(bands, 0);
  for (size_t b = 0; b < bands; ++b) {
    spread[b] = std::count(seen.begin() + b * cells, seen.begin() + (b + 1) * cells, 1);
  }
  const double min_spread = std::max(
      1.0, kMinSpread * static_cast<double>(*std::max_element(spread.begin(), spread.end())));
  const int max_sparse = static_cast<int>(kMaxVerticalGap / kBand);
  // From the top band down to the first gap of more than max_sparse sparse bands.
  int bottom = static_cast<int>(bands) - 1, sparse = 0;
  for (int b = bottom - 1; b >= 0 && sparse <= max_sparse; --b) {
    if (static_cast<double>(spread[b]) >= min_spread) {
      bottom = b;
      sparse = 0;
    } else {
      ++sparse;
    }
  }
  return z_lo + kBand * bottom;
}

}  // namespace tacs::walls
