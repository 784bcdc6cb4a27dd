#include "tacs_graphs/rooms/voxel_free_space.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <unordered_set>

namespace tacs {
namespace {

// Three voxel indices in one key, 21 bits each: distinct voxels get distinct keys within +-2^20
// voxels of the origin (+-10 km at 1 cm), unlike a hash of them (two voxels sharing a hash would
// count as one).
int64_t packVoxel(int64_t vx, int64_t vy, int64_t vz) {
  constexpr uint64_t kMask = (uint64_t{1} << 21) - 1;
  return static_cast<int64_t>(((static_cast<uint64_t>(vx) & kMask) << 42) |
                              ((static_cast<uint64_t>(vy) & kMask) << 21) |
                              (static_cast<uint64_t>(vz) & kMask));
}

}  // namespace

VoxelFreeSpace::VoxelFreeSpace(const VoxelFreeSpaceConfig& config) : config_(config) {
  config_.validate();
}

void VoxelFreeSpace::clear() {
  cells_.clear();
  keyframes_.clear();
}

int64_t VoxelFreeSpace::cellIndex(double v) const {
  return static_cast<int64_t>(std::floor(v / config_.resolution));
}

void VoxelFreeSpace::integrate(uint32_t keyframe_id, const PointCloud& cloud_in_base,
                               const Pose3& T_map_base, const Eigen::Vector3d& sensor_in_base) {
  const double floor_z = T_map_base.translation().z();
  const double z_lo = floor_z + config_.band_min, z_hi = floor_z + config_.band_max;
  const Eigen::Vector3d origin = T_map_base * sensor_in_base;
  keyframes_.emplace_back(keyframe_id, T_map_base.translation());
  // Downsample: one return per voxel of `downsample`.
  std::unordered_set<int64_t> voxels;
  std::vector<Eigen::Vector3d> points;
  for (const auto& q : cloud_in_base.points) {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    const Eigen::Vector3d p = T_map_base * Eigen::Vector3d(q.x, q.y, q.z);
    if (config_.downsample > 0.0) {
      const int64_t vx = static_cast<int64_t>(std::floor(p.x() / config_.downsample));
      const int64_t vy = static_cast<int64_t>(std::floor(p.y() / config_.downsample));
      const int64_t vz = static_cast<int64_t>(std::floor(p.z() / config_.downsample));
      if (!voxels.insert(packVoxel(vx, vy, vz)).second) continue;
    }
    points.push_back(p);
  }
  const double step = config_.resolution;
  for (const auto& p : points) {
    Eigen::Vector3d dir = p - origin;
    const double range = dir.norm();
    if (range < 1e-6) continue;
    dir /= range;
    // Clip the ray to the band and the ray length.
    double t0 = 0.0, t1 = std::min(range, config_.max_ray_length);
    if (std::abs(dir.z()) > 1e-9) {
      double ta = (z_lo - origin.z()) / dir.z(), tb = (z_hi - origin.z()) / dir.z();
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    } else if (origin.z() < z_lo || origin.z() > z_hi) {
      continue;
    }
    const bool hit = range <= config_.max_ray_length && p.z() >= z_lo && p.z() <= z_hi;
    const int64_t hit_x = cellIndex(p.x()), hit_y = cellIndex(p.y());
    if (t1 > t0) {
      int64_t last = std::numeric_limits<int64_t>::min();
      for (double t = t0; t <= t1; t += step) {
        const Eigen::Vector3d s = origin + t * dir;
        const int64_t ix = cellIndex(s.x()), iy = cellIndex(s.y());
        if (hit && ix == hit_x && iy == hit_y) break;
        const int64_t k = key(ix, iy);
        if (k == last) continue;
        last = k;
        Cell& c = cells_[k];
        if (c.free < std::numeric_limits<uint16_t>::max()) ++c.free;
        c.floor_z = static_cast<float>(floor_z);
      }
    }
    if (hit) {
      Cell& c = cells_[key(hit_x, hit_y)];
      if (c.hits < std::numeric_limits<uint16_t>::max()) ++c.hits;
      c.floor_z = static_cast<float>(floor_z);
    }
  }
}

namespace {

enum CellState : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };
constexpr int kDx4[4] = {1, -1, 0, 0}, kDy4[4] = {0, 0, 1, -1};

// The known cells as a dense grid: cell (x, y) is index y * w + x, at map cell (x0 + x, y0 + y).
struct SliceGrid {
  int64_t x0 = 0, y0 = 0;
  int w = 0, h = 0;
  std::vector<uint8_t> state;
  std::vector<float> floor_z;

  size_t size() const { return state.size(); }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  size_t at(int x, int y) const { return static_cast<size_t>(y) * w + x; }

  // Calls fn(j) for the free 4-neighbours j of cell i.
  template <class Fn>
  void forFreeNeighbours(size_t i, const Fn& fn) const {
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    for (int k = 0; k < 4; ++k) {
      const int nx = x + kDx4[k], ny = y + kDy4[k];
      if (!inside(nx, ny)) continue;
      const size_t j = at(nx, ny);
      if (state[j] == kFree) fn(j);
    }
  }
};

// Distance to the nearest occupied cell, in cells: two-pass chamfer (1, sqrt 2).
std::vector<float> chamferDistance(const SliceGrid& g) {
  std::vector<float> dist(g.size(), std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < g.size(); ++i) {
    if (g.state[i] == kOccupied) dist[i] = 0.0f;
  }
  const float diag = std::sqrt(2.0f);
  const auto relax = [&](int x, int y, int dx, int dy, float cost) {
    if (!g.inside(x + dx, y + dy)) return;
    float& d = dist[g.at(x, y)];
    d = std::min(d, dist[g.at(x + dx, y + dy)] + cost);
  };
  for (int y = 0; y < g.h; ++y) {
    for (int x = 0; x < g.w; ++x) {
      relax(x, y, -1, 0, 1.f);
      relax(x, y, 0, -1, 1.f);
      relax(x, y, -1, -1, diag);
      relax(x, y, 1, -1, diag);
    }
  }
  for (int y = g.h - 1; y >= 0; --y) {
    for (int x = g.w - 1; x >= 0; --x) {
      relax(x, y, 1, 0, 1.f);
      relax(x, y, 0, 1, 1.f);
      relax(x, y, 1, 1, diag);
      relax(x, y, -1, 1, diag);
    }
  }
  return dist;
}

// Core cells (free, beyond `clearance` cells from an obstacle) -> 4-connected components:
// a label per cell (-1: none) and the size of each component.
std::vector<int> labelCores(const SliceGrid& g, const std::vector<float>& dist, float clearance,
                            std::vector<size_t>* sizes) {
  std::vector<int> label(g.size(), -1);
  const auto isCore = [&](size_t i) { return dist[i] > clearance && label[i] < 0; };
  for (size_t s = 0; s < g.size(); ++s) {
    if (g.state[s] != kFree || !isCore(s)) continue;
    const int id = static_cast<int>(sizes->size());
    std::vector<size_t> stack{s};
    label[s] = id;
    size_t count = 0;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      ++count;
      g.forFreeNeighbours(i, [&](size_t j) {
        if (!isCore(j)) return;
        label[j] = id;
        stack.push_back(j);
      });
    }
    sizes->push_back(count);
  }
  return label;
}

// Drops the components below `min_area` and gives the cut free cells to the nearest remaining
// component (breadth-first over free cells), as S-Graphs+ re-attaches removed skeleton vertices.
void growIntoCutCells(const SliceGrid& g, const std::vector<size_t>& sizes, double cell_area,
                      double min_area, std::vector<int>* label) {
  std::deque<size_t> frontier;
  for (size_t i = 0; i < g.size(); ++i) {
    if ((*label)[i] < 0) continue;
    if (sizes[(*label)[i]] * cell_area < min_area) {
      (*label)[i] = -1;
    } else {
      frontier.push_back(i);
    }
  }
  while (!frontier.empty()) {
    const size_t i = frontier.front();
    frontier.pop_front();
    g.forFreeNeighbours(i, [&](size_t j) {
      if ((*label)[j] >= 0) return;
      (*label)[j] = (*label)[i];
      frontier.push_back(j);
    });
  }
}

// The cells (VoxelFreeSpace::cells_, keyed by key(ix, iy)) as a dense grid; a cell with
// `min_hits` returns is occupied, else free when a ray crossed it.
template <class Cells>
SliceGrid rasterize(const Cells& cells, int min_hits) {
  SliceGrid g;
  int64_t x1 = std::numeric_limits<int64_t>::min(), y1 = x1;
  g.x0 = g.y0 = std::numeric_limits<int64_t>::max();
  for (const auto& [k, c] : cells) {
    const int64_t ix = k >> 32, iy = static_cast<int32_t>(k & 0xffffffff);
    g.x0 = std::min(g.x0, ix);
    x1 = std::max(x1, ix);
    g.y0 = std::min(g.y0, iy);
    y1 = std::max(y1, iy);
  }
  g.w = static_cast<int>(x1 - g.x0 + 1);
  g.h = static_cast<int>(y1 - g.y0 + 1);
  g.state.assign(static_cast<size_t>(g.w) * g.h, kUnknown);
  g.floor_z.assign(g.state.size(), 0.0f);
  for (const auto& [k, c] : cells) {
    const int64_t ix = k >> 32, iy = static_cast<int32_t>(k & 0xffffffff);
    const size_t i = g.at(static_cast<int>(ix - g.x0), static_cast<int>(iy - g.y0));
    g.state[i] = c.hits >= min_hits ? kOccupied : (c.free > 0 ? kFree : kUnknown);
    g.floor_z[i] = c.floor_z;
  }
  return g;
}

}  // namespace

std::vector<VoxelFreeSpace::Cluster> VoxelFreeSpace::clusters() const {
  std::vector<Cluster> out;
  if (cells_.empty()) return out;
  const SliceGrid g = rasterize(cells_, config_.min_hits);
  const float clearance = static_cast<float>(config_.doorway_clearance / config_.resolution);
  std::vector<size_t> sizes;
  std::vector<int> label = labelCores(g, chamferDistance(g), clearance, &sizes);
  const double r = config_.resolution;
  growIntoCutCells(g, sizes, r * r, config_.min_cluster_area, &label);

  std::vector<int> index(sizes.size(), -1);  // component -> cluster in `out`
  for (size_t i = 0; i < g.size(); ++i) {
    if (label[i] < 0) continue;
    if (index[label[i]] < 0) {
      index[label[i]] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[index[label[i]]].points.emplace_back((g.x0 + static_cast<double>(i % g.w) + 0.5) * r,
                                             (g.y0 + static_cast<double>(i / g.w) + 0.5) * r,
                                             g.floor_z[i]);
  }
  for (const auto& [id, p] : keyframes_) {
    const int64_t ix = cellIndex(p.x()) - g.x0, iy = cellIndex(p.y()) - g.y0;
    if (ix < 0 || iy < 0 || ix >= g.w || iy >= g.h) continue;
    const int l = label[g.at(static_cast<int>(ix), static_cast<int>(iy))];
    if (l >= 0 && index[l] >= 0) out[index[l]].keyframe_ids.push_back(id);
  }
  std::stable_sort(out.begin(), out.end(), [](const Cluster& a, const Cluster& b) {
    return a.points.size() > b.points.size();
  });
  return out;
}

}  // namespace tacs
