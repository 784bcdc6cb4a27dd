#include "tacs_graphs/rooms/voxel_free_space.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <unordered_set>

namespace tacs {

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
      if (!voxels.insert((vx * 73856093) ^ (vy * 19349663) ^ (vz * 83492791)).second) continue;
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

std::vector<VoxelFreeSpace::Cluster> VoxelFreeSpace::clusters() const {
  std::vector<Cluster> out;
  if (cells_.empty()) return out;
  // Dense grid over the known cells.
  int64_t x0 = std::numeric_limits<int64_t>::max(), y0 = x0,
          x1 = std::numeric_limits<int64_t>::min(), y1 = x1;
  for (const auto& [k, c] : cells_) {
    const int64_t ix = k >> 32, iy = static_cast<int32_t>(k & 0xffffffff);
    x0 = std::min(x0, ix);
    x1 = std::max(x1, ix);
    y0 = std::min(y0, iy);
    y1 = std::max(y1, iy);
  }
  const int w = static_cast<int>(x1 - x0 + 1), h = static_cast<int>(y1 - y0 + 1);
  const size_t n = static_cast<size_t>(w) * h;
  enum : uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };
  std::vector<uint8_t> state(n, kUnknown);
  std::vector<float> floor_z(n, 0.0f);
  for (const auto& [k, c] : cells_) {
    const int64_t ix = k >> 32, iy = static_cast<int32_t>(k & 0xffffffff);
    const size_t i = static_cast<size_t>(iy - y0) * w + (ix - x0);
    state[i] = c.hits >= config_.min_hits ? kOccupied : (c.free > 0 ? kFree : kUnknown);
    floor_z[i] = c.floor_z;
  }
  // Distance to the nearest occupied cell: two-pass chamfer (1, sqrt 2), in cells.
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> dist(n, inf);
  for (size_t i = 0; i < n; ++i) {
    if (state[i] == kOccupied) dist[i] = 0.0f;
  }
  const float diag = std::sqrt(2.0f);
  auto relax = [&](int x, int y, int dx, int dy, float cost) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
    float& d = dist[static_cast<size_t>(y) * w + x];
    d = std::min(d, dist[static_cast<size_t>(ny) * w + nx] + cost);
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      relax(x, y, -1, 0, 1.f);
      relax(x, y, 0, -1, 1.f);
      relax(x, y, -1, -1, diag);
      relax(x, y, 1, -1, diag);
    }
  }
  for (int y = h - 1; y >= 0; --y) {
    for (int x = w - 1; x >= 0; --x) {
      relax(x, y, 1, 0, 1.f);
      relax(x, y, 0, 1, 1.f);
      relax(x, y, 1, 1, diag);
      relax(x, y, -1, 1, diag);
    }
  }
  // Core cells (free, beyond the doorway clearance) -> 4-connected components.
  const float clearance = static_cast<float>(config_.doorway_clearance / config_.resolution);
  std::vector<int> label(n, -1);
  std::vector<size_t> sizes;
  const int dx4[4] = {1, -1, 0, 0}, dy4[4] = {0, 0, 1, -1};
  for (size_t s = 0; s < n; ++s) {
    if (state[s] != kFree || dist[s] <= clearance || label[s] >= 0) continue;
    const int id = static_cast<int>(sizes.size());
    std::vector<size_t> stack{s};
    label[s] = id;
    size_t count = 0;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      ++count;
      const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
      for (int k = 0; k < 4; ++k) {
        const int nx = x + dx4[k], ny = y + dy4[k];
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const size_t j = static_cast<size_t>(ny) * w + nx;
        if (state[j] == kFree && dist[j] > clearance && label[j] < 0) {
          label[j] = id;
          stack.push_back(j);
        }
      }
    }
    sizes.push_back(count);
  }
  const double cell_area = config_.resolution * config_.resolution;
  std::deque<size_t> frontier;
  for (size_t i = 0; i < n; ++i) {
    if (label[i] < 0) continue;
    if (sizes[label[i]] * cell_area < config_.min_cluster_area) {
      label[i] = -1;
    } else {
      frontier.push_back(i);
    }
  }
  // Cut free cells go to the nearest cluster (breadth-first over free cells).
  while (!frontier.empty()) {
    const size_t i = frontier.front();
    frontier.pop_front();
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    for (int k = 0; k < 4; ++k) {
      const int nx = x + dx4[k], ny = y + dy4[k];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const size_t j = static_cast<size_t>(ny) * w + nx;
      if (state[j] == kFree && label[j] < 0) {
        label[j] = label[i];
        frontier.push_back(j);
      }
    }
  }
  std::vector<int> index(sizes.size(), -1);
  for (size_t i = 0; i < n; ++i) {
    if (label[i] < 0) continue;
    if (index[label[i]] < 0) {
      index[label[i]] = static_cast<int>(out.size());
      out.emplace_back();
    }
    const double r = config_.resolution;
    out[index[label[i]]].points.emplace_back((x0 + static_cast<double>(i % w) + 0.5) * r,
                                             (y0 + static_cast<double>(i / w) + 0.5) * r,
                                             floor_z[i]);
  }
  for (const auto& [id, p] : keyframes_) {
    const int64_t ix = cellIndex(p.x()) - x0, iy = cellIndex(p.y()) - y0;
    if (ix < 0 || iy < 0 || ix >= w || iy >= h) continue;
    const int l = label[static_cast<size_t>(iy) * w + ix];
    if (l >= 0 && index[l] >= 0) out[index[l]].keyframe_ids.push_back(id);
  }
  std::stable_sort(out.begin(), out.end(), [](const Cluster& a, const Cluster& b) {
    return a.points.size() > b.points.size();
  });
  return out;
}

}  // namespace tacs
