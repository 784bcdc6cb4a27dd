// Completion of unobserved tri-grid nodes: the sensor's blind disc under the robot, then BGK
// inference (Bayesian generalized kernel with the sparse kernel of Melkumyan and Ramos, as B-TMS
// does inside the tri-grid) for nodes in ring gaps and occlusion shadows.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "tri_grid.h"

namespace tacs::trav {

namespace {

bool isTarget(const NodeModel& m) { return m.label == TravLabel::kUnknown && !m.inferred; }

// Sparse kernel: smooth, exactly zero beyond the length scale, so evidence stays local.
double sparseKernel(double d, double length, double sigma0) {
  if (d >= length) return 0.0;
  const double r = d / length;
  return sigma0 * ((2.0 + std::cos(2.0 * M_PI * r)) / 3.0 * (1.0 - r) +
                   std::sin(2.0 * M_PI * r) / (2 * M_PI));
}

void setInferredGround(NodeModel* m, const Eigen::Vector3d& normal, double z, double variance) {
  m->label = TravLabel::kGround;
  m->inferred = true;
  m->has_plane = true;
  m->normal = normal;
  m->position.z() = z;
  m->d = -normal.dot(m->position);
  m->variance = static_cast<float>(variance);
}

// True when the straight line from the robot to node k crosses a node that is no ground (a
// wall, a box): the node lies behind it, in its shadow, not in the sensor's blind disc.
bool behindObstacle(const TriGrid& grid, const std::vector<NodeModel>& models, int k) {
  const Eigen::Vector2d target = grid.centroid(k);
  const int steps = static_cast<int>(std::ceil(4.0 * target.norm() / grid.resolution()));
  for (int i = 1; i < steps; ++i) {
    const Eigen::Vector2d q = target * (static_cast<double>(i) / steps);
    const int node = grid.nodeAt(q.x(), q.y());
    if (node >= 0 && node != k && models[node].label == TravLabel::kNonGround) return true;
  }
  return false;
}

}  // namespace

double fillBlindDisc(const TriGrid& grid, const TraversabilityConfig& config,
                     std::vector<NodeModel>* models) {
  // The nearest observed ground around the robot bounds the blind disc.
  double r_min = std::numeric_limits<double>::infinity();
  for (const NodeModel& m : *models) {
    if (m.isGround() && !m.inferred &&
        std::abs(m.position.z() - config.robot_floor_z) <= 2 * config.max_step) {
      r_min = std::min(r_min, m.position.head<2>().norm());
    }
  }
  if (!std::isfinite(r_min) || r_min <= grid.resolution() || r_min > config.blind_radius_max) {
    return 0.0;
  }
  // Least squares z = a x + b y + c over the ring of ground nodes just outside the disc.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int quadrants = 0, count = 0;
  const double ring = r_min + 2 * grid.resolution();
  for (const NodeModel& m : *models) {
    const double r = m.position.head<2>().norm();
    if (!m.isGround() || m.inferred || r > ring) continue;
    const Eigen::Vector3d row(m.position.x(), m.position.y(), 1.0);
    A += row * row.transpose();
    rhs += row * m.position.z();
    quadrants |= 1 << ((m.position.x() >= 0 ? 1 : 0) + (m.position.y() >= 0 ? 2 : 0));
    ++count;
  }
  // The ring must surround the robot (3 of 4 quadrants) for the disc to be interpolated.
  const int nq = __builtin_popcount(quadrants);
  if (count < 6 || nq < 3) return 0.0;
  const Eigen::Vector3d abc = A.ldlt().solve(rhs);
  if (std::abs(abc.z() - config.robot_floor_z) > config.max_step) return 0.0;
  const Eigen::Vector3d normal = Eigen::Vector3d(-abc.x(), -abc.y(), 1.0).normalized();
  if (normal.z() < std::cos(config.max_slope_deg * M_PI / 180.0)) return 0.0;
  double sq = 0.0;
  for (const NodeModel& m : *models) {
    if (!m.isGround() || m.inferred || m.position.head<2>().norm() > ring) continue;
    const double e =
        m.position.z() - (abc.x() * m.position.x() + abc.y() * m.position.y() + abc.z());
    sq += e * e;
  }
  const double variance = sq / count + config.plane_distance * config.plane_distance;
  for (NodeModel& m : *models) {
    if (!isTarget(m) || m.position.head<2>().norm() >= r_min) continue;
    if (behindObstacle(grid, *models, static_cast<int>(&m - models->data()))) continue;
    const double z = abc.x() * m.position.x() + abc.y() * m.position.y() + abc.z();
    setInferredGround(&m, normal, z, variance);
  }
  return r_min;
}

namespace {

// Kernel value and direction octant for every (cell offset, source triangle, target triangle):
// centroid offsets take few distinct values on the grid, so no trigonometry per pair.
struct KernelTable {
  struct Entry {
    double k;
    int sector;
  };
  int reach = 0;  // [cells] the kernel's support
  int side = 0;   // 2 * reach + 1
  std::vector<Entry> entries;

  KernelTable(const TriGrid& grid, const TraversabilityConfig& config) {
    const double l = config.bgk_length_scale;
    reach = static_cast<int>(std::ceil(l / grid.resolution())) + 1;
    side = 2 * reach + 1;
    entries.resize(static_cast<size_t>(side) * side * 16);
    const int n = grid.cells();
    const int centre = (n / 2 * n + n / 2) * 4;
    for (int dr = -reach; dr <= reach; ++dr) {
      for (int dc = -reach; dc <= reach; ++dc) {
        for (int tj = 0; tj < 4; ++tj) {
          for (int ti = 0; ti < 4; ++ti) {
            const Eigen::Vector2d off = grid.centroid(centre + tj) - grid.centroid(centre + ti) +
                                        grid.resolution() * Eigen::Vector2d(dc, dr);
            const double angle = std::atan2(off.y(), off.x()) + M_PI;  // [0, 2 pi]
            entries[index(dr, dc, tj, ti)] = {sparseKernel(off.norm(), l, config.bgk_sigma0),
                                              std::min(7, static_cast<int>(angle / (M_PI / 4)))};
          }
        }
      }
    }
  }
  size_t index(int dr, int dc, int tri_source, int tri_target) const {
    return ((static_cast<size_t>(dr + reach) * side + (dc + reach)) * 4 + tri_source) * 4 +
           tri_target;
  }
};

// Scatters the evidence of every observed node to the unobserved nodes within the kernel.
void scatterEvidence(const TriGrid& grid, const KernelTable& table,
                     const std::vector<NodeModel>& models, std::vector<int>* slots,
                     std::vector<Evidence>* evidences) {
  const int n = grid.cells(), reach = table.reach;
  std::vector<int>& slot = *slots;
  std::vector<Evidence>& evidence = *evidences;
  for (size_t j = 0; j < models.size(); ++j) {
    const NodeModel& src = models[j];
    if (src.inferred || src.label == TravLabel::kUnknown) continue;
    const bool ground = src.isGround();
    const int cell = static_cast<int>(j / 4), row0 = cell / n, col0 = cell % n;
    const int tri_j = static_cast<int>(j % 4);
    for (int row = std::max(0, row0 - reach); row <= std::min(n - 1, row0 + reach); ++row) {
      for (int col = std::max(0, col0 - reach); col <= std::min(n - 1, col0 + reach); ++col) {
        for (int tri = 0; tri < 4; ++tri) {
          const int i = (row * n + col) * 4 + tri;
          if (!isTarget(models[i])) continue;
          const KernelTable::Entry& ke =
              table.entries[table.index(row0 - row, col0 - col, tri_j, tri)];
          if (ke.k <= 0.0) continue;
          if (slot[i] < 0) {
            slot[i] = static_cast<int>(evidence.size());
            evidence.emplace_back();
          }
          Evidence& e = evidence[slot[i]];
          if (!ground) {
            e.nonground += ke.k;
            continue;
          }
          const Eigen::Vector2d& at = models[i].position.head<2>();
          const double z = src.heightAt(at.x(), at.y());
          e.ground += ke.k;
          e.z += ke.k * z;
          e.zz += ke.k * z * z;
          e.normal += ke.k * src.normal;
          e.sector[ke.sector] += ke.k;
        }
      }
    }
  }
}

// Beta posterior of "ground" with a uniform prior; infers only where the ground evidence
// surrounds the node: a drop-off edge or a wall has evidence on one side only.
void inferFromEvidence(const TraversabilityConfig& config, const std::vector<int>& slot,
                       const std::vector<Evidence>& evidence, std::vector<NodeModel>* models) {
  for (size_t i = 0; i < models->size(); ++i) {
    if (slot[i] < 0) continue;
    const Evidence& e = evidence[slot[i]];
    const double p = (1.0 + e.ground) / (2.0 + e.ground + e.nonground);
    if (e.ground < config.bgk_min_support || p < config.bgk_min_ground_prob) continue;
    const int dominant = static_cast<int>(std::max_element(e.sector, e.sector + 8) - e.sector);
    const double opposite =
        e.sector[(dominant + 3) % 8] + e.sector[(dominant + 4) % 8] + e.sector[(dominant + 5) % 8];
    if (opposite < config.bgk_min_opposite * e.ground) continue;
    const double z = e.z / e.ground;
    const double rel = z - config.robot_floor_z;
    if (rel > config.max_ground_height || rel < config.min_ground_height) continue;
    // Spread of the neighbours' predictions plus a prior term that shrinks with the evidence.
    const double variance = std::max(0.0, e.zz / e.ground - z * z) +
                            config.max_step * config.max_step / (1.0 + e.ground);
    setInferredGround(&(*models)[i], e.normal.normalized(), z, variance);
  }
}

}  // namespace

void inferUnobserved(const TriGrid& grid, const TraversabilityConfig& config,
                     std::vector<NodeModel>* models, std::vector<int>* slots,
                     std::vector<Evidence>* evidences) {
  slots->assign(models->size(), -1);
  evidences->clear();
  const KernelTable table(grid, config);
  scatterEvidence(grid, table, *models, slots, evidences);
  inferFromEvidence(config, *slots, *evidences, models);
}

}  // namespace tacs::trav
