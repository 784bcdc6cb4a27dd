#include "tacs_graphs/traversability/traversability_mapper.h"

#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>

#include "tacs_graphs/common/timing.h"
#include "tri_grid.h"

namespace tacs {

std::vector<std::pair<uint32_t, uint32_t>> TravGraph::safeEdges() const {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const auto& e : edges) {
    if (nodes[e.first].safe && nodes[e.second].safe) out.push_back(e);
  }
  return out;
}

size_t TravGraph::countTraversable() const {
  size_t n = 0;
  for (const TravNode& v : nodes) n += v.traversable ? 1 : 0;
  return n;
}

size_t TravGraph::countSafe() const {
  size_t n = 0;
  for (const TravNode& v : nodes) n += v.safe ? 1 : 0;
  return n;
}

TravGraph TravGraph::transformed(const Pose3& T_a_b) const {
  TravGraph out = *this;
  for (TravNode& v : out.nodes) {
    v.position = T_a_b * v.position;
    v.normal = T_a_b.linear() * v.normal;
  }
  return out;
}

TraversabilityMapper::TraversabilityMapper(const TraversabilityConfig& config) : config_(config) {
  config_.validate();
}

namespace {

using trav::NodeModel;

void appendWarning(std::string* warning, const std::string& text) {
  if (!warning->empty()) *warning += "; ";
  *warning += text;
}

// A node the robot can stand on: ground (observed or inferred), its centre clear of obstacles.
bool passable(const NodeModel& m, const TraversabilityConfig& c) {
  return m.isGround() && m.center_clearance > c.min_clearance;
}

// An edge the robot can move along: LCC holds and the straight move stays clear of obstacles,
// so a thin wall seen as one line of points is never crossed between two clear centroids.
bool edgePasses(const NodeModel& s, const NodeModel& t, const trav::ClearanceField& field,
                const TraversabilityConfig& c) {
  return trav::lccPasses(s, t, c) &&
         field.segmentClear(s.position.head<2>(), t.position.head<2>(), c.min_clearance);
}

// The root: the passable node nearest to the robot at the height of its floor.
int findRoot(const trav::TriGrid& grid, const std::vector<NodeModel>& models,
             const TraversabilityConfig& c) {
  const int r = static_cast<int>(std::ceil(c.root_search_radius / grid.resolution()));
  const int center = grid.nodeAt(0.0, 0.0) / 4, n = grid.cells();
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int row = center / n - r; row <= center / n + r; ++row) {
    for (int col = center % n - r; col <= center % n + r; ++col) {
      if (row < 0 || col < 0 || row >= n || col >= n) continue;
      for (int tri = 0; tri < 4; ++tri) {
        const int k = (row * n + col) * 4 + tri;
        const NodeModel& m = models[k];
        if (!passable(m, c) || std::abs(m.position.z() - c.robot_floor_z) > c.max_step) continue;
        const double d = m.position.head<2>().norm() + (m.inferred ? 1e-3 : 0.0);
        if (d <= c.root_search_radius + grid.resolution() && d < best_d) {
          best_d = d;
          best = k;
        }
      }
    }
  }
  return best;
}

// Breadth-first search over edge-adjacent passable nodes joined by LCC-passing edges. No
// re-seeding: the result is the robot's connected component.
void searchTraversable(const trav::TriGrid& grid, const std::vector<NodeModel>& models,
                       const trav::ClearanceField& field, int root, const TraversabilityConfig& c,
                       std::vector<char>* reached_out) {
  std::vector<char>& reached = *reached_out;
  reached.assign(models.size(), 0);
  if (root < 0) return;
  std::deque<int> queue{root};
  reached[root] = 1;
  int nb[3];
  while (!queue.empty()) {
    const int s = queue.front();
    queue.pop_front();
    grid.neighbours(s, nb);
    for (int t : nb) {
      if (t < 0 || reached[t] || !passable(models[t], c)) continue;
      if (!edgePasses(models[s], models[t], field, c)) continue;
      reached[t] = 1;
      queue.push_back(t);
    }
  }
}

TravGraph buildGraph(const trav::TriGrid& grid, const std::vector<NodeModel>& models,
                     const trav::ClearanceField& field, const std::vector<char>& reached, int root,
                     const TraversabilityConfig& c) {
  TravGraph graph;
  std::vector<int> index(models.size(), -1);
  for (size_t k = 0; k < models.size(); ++k) {
    const NodeModel& m = models[k];
    if (!trav::hasContent(m)) continue;  // nothing known
    TravNode v;
    v.position = m.position;
    v.normal = m.normal;
    v.label = m.label;
    v.inferred = m.inferred;
    v.variance = m.variance;
    v.clearance = m.clearance;
    v.traversable = reached[k] != 0;
    v.safe = v.traversable && m.clearance >= c.safe_clearance;
    index[k] = static_cast<int>(graph.nodes.size());
    graph.nodes.push_back(v);
  }
  int nb[3];
  for (size_t k = 0; k < models.size(); ++k) {
    if (!reached[k]) continue;
    grid.neighbours(static_cast<int>(k), nb);
    for (int t : nb) {
      if (t > static_cast<int>(k) && reached[t] && edgePasses(models[k], models[t], field, c)) {
        graph.edges.emplace_back(index[k], index[t]);
      }
    }
  }
  graph.root = root >= 0 ? index[root] : -1;
  return graph;
}

// Mean normal of the observed ground near the robot: a tilt means the scan is not gravity-aligned.
double groundTiltDeg(const std::vector<NodeModel>& models, const std::vector<char>& reached) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < models.size(); ++k) {
    const NodeModel& m = models[k];
    if (reached[k] && !m.inferred && m.position.head<2>().norm() < 4.0) sum += m.normal;
  }
  if (sum.norm() < 1e-9) return 0.0;
  return std::acos(std::min(1.0, sum.normalized().z())) * 180.0 / M_PI;
}

}  // namespace

TraversabilityResult TraversabilityMapper::process(const PointCloud& scan_in_base) const {
  Stopwatch watch;
  const TraversabilityConfig& c = config_;
  TraversabilityResult result;
  result.ground.reset(new PointCloud);
  result.obstacles.reset(new PointCloud);

  const trav::TriGrid grid(c.resolution, c.max_range);
  thread_local trav::Workspace ws;
  std::vector<NodeModel>& models = ws.models;
  const trav::BucketedScan& scan = ws.scan;
  trav::bucketScan(scan_in_base, grid, c, &ws.scan, &models);
  if (scan.valid == 0) {
    appendWarning(&result.warning, "empty scan: no finite point inside the grid");
  }
  trav::fitNodePlanes(scan, grid, c, &models);
  trav::fillBlindDisc(grid, c, &models);
  trav::inferUnobserved(grid, c, &models, &ws.slot, &ws.evidence);
  trav::classifyPoints(grid, models, c, &ws.scan);
  const trav::ClearanceField field(scan, grid, c, &models, &ws.distance);

  const int root = findRoot(grid, models, c);
  searchTraversable(grid, models, field, root, c, &ws.reached);
  const std::vector<char>& reached = ws.reached;
  result.graph = buildGraph(grid, models, field, reached, root, c);

  result.ground->reserve(scan.valid);
  result.obstacles->reserve(scan.valid / 2);
  for (size_t i = 0; i < scan.point_class.size(); ++i) {
    if (scan.node_of[i] < 0) continue;
    if (scan.point_class[i] == trav::kGroundPoint) {
      result.ground->push_back(scan_in_base.points[i]);
    } else if (scan.point_class[i] == trav::kObstaclePoint) {
      result.obstacles->push_back(scan_in_base.points[i]);
    }
  }
  result.ground_points = result.ground->size();
  result.nonground_points = scan.valid - result.ground_points;

  if (scan.valid > 0 && result.ground_points == 0) {
    appendWarning(&result.warning, "no ground found in the scan");
  }
  if (scan.valid > 0 && root < 0) {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "no traversable ground under the robot (expected near z = %.2f m in the base "
                  "frame): is the sensor's mounting height given (frames.base_to_sensor, the "
                  "launch argument base_to_sensor), or for a hand-held sensor "
                  "traversability.find_floor_under_base (config/handheld.yaml)?",
                  c.robot_floor_z);
    appendWarning(&result.warning, text);
  }
  const double tilt = groundTiltDeg(models, reached);
  if (tilt > c.tilt_warning_deg) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "ground around the robot tilts %.1f deg from the base z axis: is the scan "
                  "gravity-aligned?",
                  tilt);
    appendWarning(&result.warning, text);
  }
  for (PointCloud* cloud : {result.ground.get(), result.obstacles.get()}) {
    cloud->header = scan_in_base.header;
    cloud->width = static_cast<uint32_t>(cloud->size());
    cloud->height = 1;
    cloud->is_dense = true;
  }
  result.time_ms = watch.elapsedMs();
  return result;
}

}  // namespace tacs
