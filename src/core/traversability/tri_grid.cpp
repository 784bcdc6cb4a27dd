// Tri-grid geometry and per-node terrain model (iterative PCA from the lowest points).
#include "tri_grid.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace tacs::trav {

TriGrid::TriGrid(double resolution, double max_range)
    : res_(resolution), cells_(static_cast<int>(std::ceil(2.0 * max_range / resolution))) {
  if (cells_ % 2 == 0) ++cells_;  // odd: the robot sits at the centre of a cell
  origin_ = -0.5 * cells_ * res_;
}

int TriGrid::nodeAt(double x, double y) const {
  const double fx = (x - origin_) / res_, fy = (y - origin_) / res_;
  if (!(fx >= 0.0 && fy >= 0.0 && fx < cells_ && fy < cells_)) return -1;
  const int col = static_cast<int>(fx), row = static_cast<int>(fy);
  const double dx = fx - col - 0.5, dy = fy - row - 0.5;
  int tri;
  if (std::abs(dx) >= std::abs(dy)) {
    tri = dx >= 0.0 ? 0 : 2;
  } else {
    tri = dy >= 0.0 ? 1 : 3;
  }
  return (row * cells_ + col) * 4 + tri;
}

Eigen::Vector2d TriGrid::centroid(int node) const {
  static const double kDx[4] = {1, 0, -1, 0}, kDy[4] = {0, 1, 0, -1};
  const int cell = node / 4, tri = node % 4;
  const int row = cell / cells_, col = cell % cells_;
  // The centroid of a quarter triangle lies a third of the way from the centre to the edge.
  return {origin_ + (col + 0.5 + kDx[tri] / 3.0) * res_,
          origin_ + (row + 0.5 + kDy[tri] / 3.0) * res_};
}

void TriGrid::neighbours(int node, int out[3]) const {
  static const int kDcol[4] = {1, 0, -1, 0}, kDrow[4] = {0, 1, 0, -1};
  const int cell = node / 4, tri = node % 4;
  out[0] = cell * 4 + (tri + 1) % 4;
  out[1] = cell * 4 + (tri + 3) % 4;
  const int row = cell / cells_ + kDrow[tri], col = cell % cells_ + kDcol[tri];
  out[2] = (row < 0 || col < 0 || row >= cells_ || col >= cells_)
               ? -1
               : (row * cells_ + col) * 4 + (tri + 2) % 4;
}

void bucketScan(const PointCloud& scan, const TriGrid& grid, const TraversabilityConfig& config,
                BucketedScan* bucketed, std::vector<NodeModel>* models) {
  BucketedScan& out = *bucketed;
  out.valid = 0;
  const size_t n = scan.size();
  out.points.resize(n);
  out.node_of.assign(n, -1);
  models->assign(grid.size(), NodeModel{});
  std::vector<uint32_t>& counts = out.counts;
  counts.assign(grid.size() + 1, 0);
  const double min_r2 = config.min_range * config.min_range;
  for (size_t i = 0; i < n; ++i) {
    const auto& q = scan.points[i];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    if (static_cast<double>(q.x) * q.x + static_cast<double>(q.y) * q.y < min_r2) continue;
    const int node = grid.nodeAt(q.x, q.y);
    if (node < 0) continue;
    out.points[i] = Eigen::Vector3f(q.x, q.y, q.z);
    out.node_of[i] = node;
    ++counts[node + 1];
    ++out.valid;
  }
  for (size_t k = 1; k < counts.size(); ++k) counts[k] += counts[k - 1];
  out.order.resize(out.valid);
  std::vector<uint32_t>& fill = out.fill;
  fill.assign(counts.begin(), counts.end() - 1);
  for (size_t i = 0; i < n; ++i) {
    if (out.node_of[i] >= 0) out.order[fill[out.node_of[i]]++] = static_cast<uint32_t>(i);
  }
  for (size_t k = 0; k < grid.size(); ++k) {
    NodeModel& m = (*models)[k];
    m.begin = counts[k];
    m.count = counts[k + 1] - counts[k];
    const Eigen::Vector2d c = grid.centroid(static_cast<int>(k));
    m.position = Eigen::Vector3d(c.x(), c.y(), config.robot_floor_z);
  }
}

namespace {

struct PlaneFit {
  Eigen::Vector3d normal, mean, line;  // line: direction of largest variance
  Eigen::Matrix3d cov;
  Eigen::Vector3d eigenvalues;  // ascending
  size_t count = 0;
};

// PCA of the selected points: the normal is the direction of least variance, pointing up. One
// pass over the points, taken relative to `ref` (a point of the node) to keep the sums small.
bool fitPlane(const std::vector<Eigen::Vector3f>& pts, const std::vector<uint32_t>& idx,
              const Eigen::Vector3f& ref, PlaneFit* fit) {
  if (idx.size() < 3) return false;
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  Eigen::Matrix3f outer = Eigen::Matrix3f::Zero();
  for (uint32_t i : idx) {
    const Eigen::Vector3f v = pts[i] - ref;
    sum += v;
    outer.noalias() += v * v.transpose();
  }
  const double inv = 1.0 / static_cast<double>(idx.size());
  const Eigen::Vector3d mean = sum.cast<double>() * inv;
  const Eigen::Matrix3d cov = outer.cast<double>() * inv - mean * mean.transpose();
  fit->mean = mean + ref.cast<double>();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  fit->eigenvalues = es.eigenvalues().cwiseMax(0.0);
  fit->normal = es.eigenvectors().col(0);
  fit->line = es.eigenvectors().col(2);
  fit->cov = cov;
  if (fit->normal.z() < 0) fit->normal = -fit->normal;
  fit->count = idx.size();
  return true;
}

// True when the node's single scan line is the lowest line on a wall or box side: most points
// from plane_distance to robot_height above the line stand in the vertical plane through it. A
// floor line in front of a wall has the wall's points behind it, off that plane. Without this test
// the level plane through a wall's lowest line makes a "floor" up to max_ground_height above the
// real one.
bool footOfVerticalFace(const BucketedScan& scan, const NodeModel& m, const PlaneFit& line,
                        const TraversabilityConfig& c) {
  const Eigen::Vector2d along = line.line.head<2>();
  if (along.norm() < 1e-6) return false;
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  constexpr double kInPlane = 0.05;  // [m] a point this close to the vertical plane lies on it
  int above = 0, in_plane = 0;
  const uint32_t* ids = scan.order.data() + m.begin;
  for (uint32_t k = 0; k < m.count; ++k) {
    const Eigen::Vector3d p = scan.points[ids[k]].cast<double>() - line.mean;
    if (p.z() <= c.plane_distance || p.z() > c.robot_height) continue;  // not the ceiling
    ++above;
    in_plane += std::abs(across.dot(p.head<2>())) < kInPlane;
  }
  return above > 0 && 2 * in_plane > above;
}

void fitNode(const BucketedScan& scan, const TraversabilityConfig& c, NodeModel* m,
             std::vector<float>* zbuf, std::vector<uint32_t>* sel) {
  const uint32_t* ids = scan.order.data() + m->begin;
  zbuf->clear();
  for (uint32_t k = 0; k < m->count; ++k) zbuf->push_back(scan.points[ids[k]].z());
  const size_t nseed = std::min<size_t>(c.seed_count, zbuf->size());
  std::nth_element(zbuf->begin(), zbuf->begin() + (nseed - 1), zbuf->end());
  double lowest = 0.0;  // mean height of the lowest points (the seed height)
  for (size_t k = 0; k < nseed; ++k) lowest += (*zbuf)[k];
  lowest /= static_cast<double>(nseed);
  m->position.z() = lowest;
  const Eigen::Vector3f ref = m->position.cast<float>();

  sel->clear();
  for (uint32_t k = 0; k < m->count; ++k) {
    if (scan.points[ids[k]].z() < lowest + c.seed_margin) sel->push_back(ids[k]);
  }
  PlaneFit fit;
  for (int it = 0; it < c.plane_iterations; ++it) {
    if (!fitPlane(scan.points, *sel, ref, &fit)) return;  // UNKNOWN
    if (it + 1 == c.plane_iterations) break;
    const double d = -fit.normal.dot(fit.mean);
    sel->clear();
    for (uint32_t k = 0; k < m->count; ++k) {
      const Eigen::Vector3f& p = scan.points[ids[k]];
      if (std::abs(fit.normal.dot(p.cast<double>()) + d) < c.plane_distance) sel->push_back(ids[k]);
    }
  }
  double thickness_var = fit.eigenvalues(0), line_penalty = 0.0;
  if (std::sqrt(fit.eigenvalues(1)) < c.min_plane_width) {
    // One scan line grazing the node: points on a line, which fixes the plane only up to a
    // rotation about it. Take the most level plane through the line (floors seen from afar); a
    // line steeper than a ground plane may be (a pole, a wall edge, a ring curving on a wall
    // close by) is no ground.
    const Eigen::Vector3d dir = fit.line;
    const Eigen::Vector3d level = Eigen::Vector3d::UnitZ() - dir.z() * dir;
    if (std::abs(dir.z()) > std::sin(c.max_slope_deg * M_PI / 180.0)) {
      m->label = TravLabel::kNonGround;
      return;
    }
    fit.normal = level.normalized();
    if (footOfVerticalFace(scan, *m, fit, c)) {
      m->label = TravLabel::kNonGround;
      return;
    }
    thickness_var = fit.normal.dot(fit.cov * fit.normal);
    line_penalty = c.plane_distance * c.plane_distance;  // weaker evidence than a true plane
  }
  m->has_plane = true;
  m->normal = fit.normal;
  m->d = -fit.normal.dot(fit.mean);
  m->variance = static_cast<float>(thickness_var + line_penalty);
  const bool flat = fit.normal.z() >= std::cos(c.max_slope_deg * M_PI / 180.0);
  if (!flat) {
    m->label = TravLabel::kNonGround;
    m->has_plane = false;  // a wall patch is no ground reference
    return;
  }
  m->position.z() = m->heightAt(m->position.x(), m->position.y());
  const double rel = m->position.z() - c.robot_floor_z;
  const bool thin = std::sqrt(thickness_var) <= c.max_plane_thickness;
  const bool plausible = rel <= c.max_ground_height && rel >= c.min_ground_height;
  m->label = (thin && plausible) ? TravLabel::kGround : TravLabel::kNonGround;
}

}  // namespace

void fitNodePlanes(const BucketedScan& scan, const TriGrid& grid,
                   const TraversabilityConfig& config, std::vector<NodeModel>* models) {
  std::vector<float> zbuf;
  std::vector<uint32_t> sel;
  for (size_t k = 0; k < grid.size(); ++k) {
    NodeModel& m = (*models)[k];
    if (m.count >= static_cast<uint32_t>(config.min_points)) fitNode(scan, config, &m, &zbuf, &sel);
  }
}

bool isGroundPoint(const NodeModel& m, const Eigen::Vector3f& p, const TraversabilityConfig& c) {
  return m.isGround() && std::abs(m.distance(p)) < c.plane_distance;
}

bool isObstaclePoint(const NodeModel& m, const Eigen::Vector3f& p, const TraversabilityConfig& c) {
  if (isGroundPoint(m, p, c)) return false;
  // Heights are taken above the node's ground plane, or the robot's floor when it has none.
  const double ground = m.isGround() ? m.heightAt(p.x(), p.y()) : c.robot_floor_z;
  const double h = p.z() - ground;
  return h >= c.obstacle_min_height && h <= c.robot_height;
}

namespace {

// Ground nodes near node k whose plane may be lent to its points: observed (not inferred) ground
// in its own or an adjacent cell, at the height of the node's lowest point (the floor under a
// wall's foot, not the top of a low box next to it).
void lendingNodes(const TriGrid& grid, const std::vector<NodeModel>& models, size_t k,
                  const BucketedScan& scan, const TraversabilityConfig& config,
                  std::vector<const NodeModel*>* out) {
  out->clear();
  const NodeModel& m = models[k];
  float lowest = std::numeric_limits<float>::infinity();
  for (uint32_t a = 0; a < m.count; ++a) {
    lowest = std::min(lowest, scan.points[scan.order[m.begin + a]].z());
  }
  const int n = grid.cells(), row = static_cast<int>(k / 4) / n, col = static_cast<int>(k / 4) % n;
  for (int r = std::max(0, row - 1); r <= std::min(n - 1, row + 1); ++r) {
    for (int q = std::max(0, col - 1); q <= std::min(n - 1, col + 1); ++q) {
      for (int tri = 0; tri < 4; ++tri) {
        const NodeModel& t = models[(r * n + q) * 4 + tri];
        if (t.isGround() && !t.inferred &&
            std::abs(t.position.z() - lowest) < config.plane_distance) {
          out->push_back(&t);
        }
      }
    }
  }
}

}  // namespace

void classifyPoints(const TriGrid& grid, const std::vector<NodeModel>& models,
                    const TraversabilityConfig& config, BucketedScan* scan) {
  scan->point_class.assign(scan->points.size(), kOtherPoint);
  // A node that is not ground itself (a wall's foot, too few points) still holds floor points:
  // the ones at the height of a nearby ground node (lendingNodes). The lent height is taken
  // level and the band is half as wide, as it is extrapolated. A point in the obstacle band of
  // its own node stays an obstacle, so lending never opens a gap in the clearance field.
  const double lent_band = 0.5 * config.plane_distance;
  std::vector<const NodeModel*> lenders;
  for (size_t k = 0; k < models.size(); ++k) {
    const NodeModel& m = models[k];
    if (m.count == 0) continue;
    if (m.isGround()) {
      lenders.clear();
    } else {
      lendingNodes(grid, models, k, *scan, config, &lenders);
    }
    for (uint32_t a = 0; a < m.count; ++a) {
      const uint32_t i = scan->order[m.begin + a];
      const Eigen::Vector3f& p = scan->points[i];
      if (isGroundPoint(m, p, config)) {
        scan->point_class[i] = kGroundPoint;
      } else if (isObstaclePoint(m, p, config)) {
        scan->point_class[i] = kObstaclePoint;
      } else {
        for (const NodeModel* t : lenders) {
          if (std::abs(p.z() - t->position.z()) < lent_band) {
            scan->point_class[i] = kGroundPoint;
            break;
          }
        }
      }
    }
  }
}

bool lccPasses(const NodeModel& s, const NodeModel& t, const TraversabilityConfig& config) {
  if (s.normal.dot(t.normal) < std::cos(config.max_normal_change_deg * M_PI / 180.0)) return false;
  const Eigen::Vector3d delta = t.position - s.position;
  return std::abs(s.normal.dot(delta)) <= config.max_step &&
         std::abs(t.normal.dot(delta)) <= config.max_step;
}

}  // namespace tacs::trav
