#include "tacs_graphs/walls/wall_extractor.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>

#include "face_bottom.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/timing.h"

namespace tacs {

void WallExtractionConfig::validate() const {
  const std::string p = "walls.extraction.";
  requireConfig(voxel_size >= 0.0, p + "voxel_size_m", "must be >= 0");
  requireConfig(min_range >= 0.0 && max_range > min_range, p + "max_range_m",
                "need 0 <= min_range < max_range");
  requireConfig(distance_threshold > 0.0, p + "distance_threshold_m", "must be > 0");
  requireConfig(ransac_iterations > 0, p + "ransac_iterations", "must be > 0");
  requireConfig(score_subsample >= 16, p + "score_subsample", "must be >= 16");
  requireConfig(sample_cell > 0.0, p + "sample_cell_m", "must be > 0");
  requireConfig(refine_iterations >= 0, p + "refine_iterations", "must be >= 0");
  requireConfig(max_planes > 0, p + "max_planes", "must be > 0");
  requireConfig(min_remaining_points >= 3, p + "min_remaining_points", "must be >= 3");
  requireConfig(min_plane_inliers >= 3, p + "min_plane_inliers", "must be >= 3");
  requireConfig(vertical_tolerance_deg > 0.0 && vertical_tolerance_deg < 45.0,
                p + "vertical_tolerance_deg", "must be in (0, 45)");
  requireConfig(horizontal_tolerance_deg > 0.0 && horizontal_tolerance_deg < 45.0,
                p + "horizontal_tolerance_deg", "must be in (0, 45)");
  requireConfig(max_gap > 0.0, p + "max_gap_m", "must be > 0");
  requireConfig(edge_band >= 0.0, p + "edge_band_m", "must be >= 0");
  requireConfig(min_wall_inliers >= 3, p + "min_wall_inliers", "must be >= 3");
  requireConfig(min_wall_length >= 0.0, p + "min_wall_length_m", "must be >= 0");
  requireConfig(min_wall_height >= 0.0, p + "min_wall_height_m", "must be >= 0");
  requireConfig(min_coverage >= 0.0 && min_coverage <= 1.0, p + "min_coverage",
                "must be in [0, 1]");
  requireConfig(min_wall_top >= 0.0, p + "min_wall_top_m", "must be >= 0 (0 = off)");
  requireConfig(max_wall_bottom >= 0.0, p + "max_wall_bottom_m", "must be >= 0 (0 = off)");
  requireConfig(fov_top_margin_deg >= 0.0 && fov_top_margin_deg < 90.0, p + "fov_top_margin_deg",
                "must be in [0, 90)");
  requireConfig(seen_over_min_points >= 0, p + "seen_over_min_points", "must be >= 0 (0 = off)");
  requireConfig(seen_over_depth >= 0.0, p + "seen_over_depth_m", "must be >= 0");
  requireConfig(seen_over_clearance >= 0.0, p + "seen_over_clearance_m", "must be >= 0");
  requireConfig(on_wall_max_depth >= 0.0, p + "on_wall_max_depth_m", "must be >= 0 (0 = off)");
  requireConfig(min_horizontal_inliers >= 3, p + "min_horizontal_inliers", "must be >= 3");
}

namespace {

using Points = std::vector<Eigen::Vector3f>;

// Integer cell key of a point (21 bits per axis, +-1e6 cells).
uint64_t cellKey(const Eigen::Vector3f& p, float inv_cell) {
  constexpr int64_t kOffset = 1 << 20;
  auto c = [&](float v) {
    return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v * inv_cell)) + kOffset) &
           0x1FFFFF;
  };
  return (c(p.x()) << 42) | (c(p.y()) << 21) | c(p.z());
}

// Dense ids for integer keys in order of first occurrence (open addressing). The storage is
// kept between calls: fresh multi-megabyte allocations cost more than the work on them.
class KeyIndexer {
 public:
  void reset(size_t max_keys) {
    for (uint32_t s : used_) keys_[s] = kEmpty;
    used_.clear();
    size_t capacity = 16;
    while (capacity < 2 * max_keys) capacity <<= 1;
    if (capacity > keys_.size()) {
      keys_.assign(capacity, kEmpty);
      ids_.resize(capacity);
    }
    mask_ = keys_.size() - 1;
  }
  uint32_t idOf(uint64_t key) {
    size_t h = ((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_;
    while (keys_[h] != kEmpty && keys_[h] != key) h = (h + 1) & mask_;
    if (keys_[h] == kEmpty) {
      keys_[h] = key;
      ids_[h] = static_cast<uint32_t>(used_.size());
      used_.push_back(static_cast<uint32_t>(h));
    }
    return ids_[h];
  }
  size_t size() const { return used_.size(); }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> ids_;
  std::vector<uint32_t> used_;
  size_t mask_ = 0;
};

// Points grouped by sampling cell, so the 3 points of a hypothesis come from one neighbourhood.
struct SampleCells {
  std::vector<uint32_t> cell_of;  // point -> cell
  std::vector<uint32_t> members;  // point indices grouped by cell
  std::vector<uint32_t> begin;    // cell -> first index into members (size cells + 1)
};

// Per-thread buffers reused by every extract() call.
struct Scratch {
  KeyIndexer indexer;
  std::vector<Eigen::Vector4f> sums;  // voxel xyz sum and count
  Points pts;
  SampleCells cells;
  std::vector<uint8_t> active;
  std::vector<uint32_t> active_list;
  std::vector<uint32_t> inliers;
  std::vector<float> sub_x, sub_y, sub_z;  // scoring subsample, one array per axis (vectorises)
};

// Range crop and voxel-centroid downsampling into scratch->pts.
void cropAndDownsample(const PointCloud& cloud, const WallExtractionConfig& cfg, Scratch* scratch) {
  const float r2_min = static_cast<float>(cfg.min_range * cfg.min_range);
  const float r2_max = static_cast<float>(cfg.max_range * cfg.max_range);
  const bool voxelize = cfg.voxel_size > 0.0;
  const float inv = voxelize ? static_cast<float>(1.0 / cfg.voxel_size) : 1.f;
  Points& pts = scratch->pts;
  auto& sums = scratch->sums;
  pts.clear();
  sums.clear();
  scratch->indexer.reset(cloud.size());
  for (const auto& q : cloud.points) {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    const Eigen::Vector3f p(q.x, q.y, q.z);
    const float r2 = p.squaredNorm();
    if (r2 < r2_min || r2 > r2_max) continue;
    if (!voxelize) {
      pts.push_back(p);
      continue;
    }
    const uint32_t id = scratch->indexer.idOf(cellKey(p, inv));
    if (id == sums.size()) sums.emplace_back(0.f, 0.f, 0.f, 0.f);
    sums[id] += Eigen::Vector4f(p.x(), p.y(), p.z(), 1.f);
  }
  for (const auto& s : sums) pts.push_back(s.head<3>() / s.w());
}

// Groups the points by sampling cell (counting sort, stable in point order).
void buildSampleCells(const Points& pts, double cell, Scratch* scratch) {
  const float inv = static_cast<float>(1.0 / cell);
  SampleCells& cells = scratch->cells;
  scratch->indexer.reset(pts.size());
  cells.cell_of.resize(pts.size());
  for (size_t i = 0; i < pts.size(); ++i)
    cells.cell_of[i] = scratch->indexer.idOf(cellKey(pts[i], inv));
  cells.begin.assign(scratch->indexer.size() + 1, 0);
  for (uint32_t c : cells.cell_of) ++cells.begin[c + 1];
  for (size_t c = 1; c < cells.begin.size(); ++c) cells.begin[c] += cells.begin[c - 1];
  cells.members.resize(pts.size());
  std::vector<uint32_t>& fill = scratch->inliers;  // borrowed as the insertion cursor
  fill.assign(cells.begin.begin(), cells.begin.end() - 1);
  for (size_t i = 0; i < pts.size(); ++i) cells.members[fill[cells.cell_of[i]]++] = uint32_t(i);
}

struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  double d = 0.0;
};

// Least-squares plane (PCA) through the given points; centroid returned for the extent.
Plane fitPlane(const Points& pts, const std::vector<uint32_t>& idx, Eigen::Vector3d* centroid) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (uint32_t i : idx) c += pts[i].cast<double>();
  c /= static_cast<double>(idx.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (uint32_t i : idx) {
    const Eigen::Vector3d q = pts[i].cast<double>() - c;
    cov.noalias() += q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Plane plane;
  plane.n = eig.eigenvectors().col(0).normalized();  // smallest eigenvalue
  plane.d = -plane.n.dot(c);
  if (centroid) *centroid = c;
  return plane;
}

void collectInliers(const Points& pts, const std::vector<uint32_t>& candidates, const Plane& pl,
                    float thr, std::vector<uint32_t>* out) {
  out->clear();
  const Eigen::Vector3f n = pl.n.cast<float>();
  const float d = static_cast<float>(pl.d);
  for (uint32_t i : candidates) {
    if (std::abs(n.dot(pts[i]) + d) < thr) out->push_back(i);
  }
}

// Where the scan was taken from and how high its beams reach.
struct View {
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();
  double top_elevation = M_PI_2;  // [rad] elevation of the highest beam seen from the viewpoint
};

// Beams nearer than this (horizontally) say little about the field of view: the elevation of a
// point on the robot's own mast or a close ceiling lamp is not the sensor's.
constexpr double kMinElevationRange = 1.0;  // [m]

View viewOf(const Points& pts, const Eigen::Vector3d& viewpoint) {
  View view;
  view.viewpoint = viewpoint;
  // The steepest slope dz / r, one atan at the end: atan is monotonic.
  double top_slope = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3f& p : pts) {
    const Eigen::Vector3d q = p.cast<double>() - viewpoint;
    const double r = q.head<2>().norm();
    if (r >= kMinElevationRange) top_slope = std::max(top_slope, q.z() / r);
  }
  if (std::isfinite(top_slope)) view.top_elevation = std::atan(top_slope);
  return view;
}

// A low surface: its top (z_top, seen at horizontal range r_top) stays below min_wall_top above
// the sensor although the scan's upper beams pass above it there, so the sensor saw over it.
bool isLowSurface(double z_top, double r_top, const View& view, const WallExtractionConfig& cfg) {
  const double above_sensor = z_top - view.viewpoint.z();
  if (cfg.min_wall_top <= 0.0 || above_sensor >= cfg.min_wall_top) return false;
  const double elevation = std::atan2(above_sensor, r_top);
  return elevation < view.top_elevation - cfg.fov_top_margin_deg * M_PI / 180.0;
}

void faceViewpoint(const Eigen::Vector3d& viewpoint, bool horizontal_only_z, Plane* pl) {
  Eigen::Vector3d v = viewpoint;
  if (!horizontal_only_z) v.z() = 0.0;  // walls: only the xy position of the sensor matters
  if (pl->n.dot(v) + pl->d < 0.0) {
    pl->n = -pl->n;
    pl->d = -pl->d;
  }
}

// What a run of inliers of a vertical plane makes: nothing (too small, not vertical, scattered),
// a wall, or a surface the sensor saw over (its top stays low while beams pass above it).
enum class RunKind { kNone, kWall, kLowSurface };

// The bounded segment of a run of inliers and what it is.
RunKind makeWallSegment(const Points& pts, const std::vector<uint32_t>& run,
                        const WallExtractionConfig& cfg, const View& view, WallSegment* wall) {
  if (run.size() < static_cast<size_t>(cfg.min_wall_inliers)) return RunKind::kNone;
  Eigen::Vector3d c;
  Plane pl = fitPlane(pts, run, &c);
  // The run's own plane must be vertical too (a model can pass the test thanks to other runs).
  if (std::abs(pl.n.z()) > std::sin(cfg.vertical_tolerance_deg * M_PI / 180.0)) {
    return RunKind::kNone;
  }
  faceViewpoint(view.viewpoint, false, &pl);
  const Eigen::Vector2d axis = wallAxis(pl.n);
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
  double z_min = t_min, z_max = -t_min;
  uint32_t top = run.front();
  for (uint32_t i : run) {
    const Eigen::Vector3d p = pts[i].cast<double>();
    const double t = axis.dot(p.head<2>() - c.head<2>());
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
    z_min = std::min(z_min, p.z());
    if (p.z() > z_max) {
      z_max = p.z();
      top = i;
    }
  }
  if (t_max - t_min < cfg.min_wall_length || z_max - z_min < cfg.min_wall_height) {
    return RunKind::kNone;
  }
  if (cfg.max_wall_bottom > 0.0 &&
      walls::connectedBottom(pts, run, axis, c, t_min, t_max) - view.viewpoint.z() >
          cfg.max_wall_bottom) {
    return RunKind::kNone;  // hangs from the ceiling
  }
  // Share of the length with inliers: a plane threading through scattered clutter covers little.
  const double bin = std::max(0.1, 2.0 * cfg.voxel_size);
  std::vector<uint8_t> occupied(static_cast<size_t>((t_max - t_min) / bin) + 1, 0);
  for (uint32_t i : run) {
    const double t = axis.dot(pts[i].head<2>().cast<double>() - c.head<2>());
    occupied[static_cast<size_t>((t - t_min) / bin)] = 1;
  }
  size_t filled = 0;
  for (uint8_t o : occupied) filled += o;
  if (static_cast<double>(filled) < cfg.min_coverage * static_cast<double>(occupied.size())) {
    return RunKind::kNone;
  }
  const Eigen::Vector2d a = c.head<2>() + t_min * axis, b = c.head<2>() + t_max * axis;
  const double z_mid = 0.5 * (z_min + z_max);
  wall->normal = pl.n;
  wall->d = pl.d;
  wall->inliers = static_cast<uint32_t>(run.size());
  wall->endpoints[0] = projectOntoWallLine(pl.n, pl.d, a, z_mid);
  wall->endpoints[1] = projectOntoWallLine(pl.n, pl.d, b, z_mid);
  wall->z_min = z_min;
  wall->z_max = z_max;
  const double r_top = (pts[top].head<2>().cast<double>() - view.viewpoint.head<2>()).norm();
  return isLowSurface(z_max, r_top, view, cfg) ? RunKind::kLowSurface : RunKind::kWall;
}

// Stretches of max_gap along a wall segment, numbered from endpoints[0].
struct Stretches {
  Stretches(const WallSegment& wall, double size)
      : e0(wall.endpoints[0]),
        u((wall.endpoints[1] - e0).normalized()),
        length(wall.length()),
        size(size),
        count(static_cast<size_t>(length / size) + 1) {}
  double along(const Eigen::Vector2d& xy) const { return u.dot(xy - e0); }
  size_t of(double t) const { return static_cast<size_t>(std::clamp(t / size, 0.0, count - 1.0)); }

  Eigen::Vector2d e0, u;
  double length, size;
  size_t count;
};

// Seen over: scan rays that cross a segment's line between its ends above its top and hit a
// surface beyond it. A wall meets the ceiling (rays over its top hit the ceiling on the near side)
// or the sky (no return); a cabinet or a partition in front of a wall lets rays over it reach the
// wall behind. Rays through doorways and windows cross below the top and do not count (rays under
// a segment do not either: through a doorway under its lintel they would). Judged per stretch,
// each with its own top (a full-height wall and a collinear half wall can make one run; only the
// half wall's stretches are seen over): returns per stretch whether seen_over_min_points such
// points were found. `stretch_of` gives the stretch of each inlier of `run`.
std::vector<uint8_t> seenOver(const Points& pts, const std::vector<uint32_t>& run,
                              const std::vector<size_t>& stretch_of, const WallSegment& wall,
                              const Stretches& stretches, const View& view,
                              const WallExtractionConfig& cfg) {
  std::vector<uint8_t> over(stretches.count, 0);
  const Eigen::Vector2d n = wall.normal.head<2>().normalized();
  const Eigen::Vector3d& v = view.viewpoint;
  const double s_v = n.dot(v.head<2>()) + wall.d;  // > 0: normals face the viewpoint
  if (s_v <= 0.0) return over;
  std::vector<double> top(stretches.count, -std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < run.size(); ++k) {
    top[stretch_of[k]] = std::max(top[stretch_of[k]], static_cast<double>(pts[run[k]].z()));
  }
  for (double& z : top) z = std::isfinite(z) ? z : wall.z_max;  // a gap in the run
  std::vector<int> count(stretches.count, 0);
  for (const Eigen::Vector3f& pf : pts) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double s_p = n.dot(p.head<2>()) + wall.d;
    if (s_p > -cfg.seen_over_depth) continue;                   // not beyond the segment's plane
    const Eigen::Vector3d c = v + s_v / (s_v - s_p) * (p - v);  // where the ray crosses it
    const double t = stretches.along(c.head<2>());
    if (t < 0.0 || t > stretches.length) continue;
    const size_t k = stretches.of(t);
    if (c.z() < top[k] + cfg.seen_over_clearance) continue;  // not over the stretch's top
    over[k] = ++count[k] >= cfg.seen_over_min_points;
  }
  return over;
}

// Where the segments of one run of inliers go: walls, or surfaces seen over.
struct RunOutput {
  std::vector<WallSegment>* walls;
  std::vector<WallSegment>* seen_over;
};

// The segments of one run of inliers: the run's segment, or, when stretches of it were seen over,
// the pieces between those stretches as walls and the stretches as surfaces seen over.
void appendWalls(const Points& pts, const std::vector<uint32_t>& run,
                 const WallExtractionConfig& cfg, const View& view, const RunOutput& out) {
  WallSegment wall;
  const RunKind kind = makeWallSegment(pts, run, cfg, view, &wall);
  if (kind == RunKind::kNone) return;
  if (cfg.seen_over_min_points <= 0 || wall.length() <= 0.0) {
    if (kind == RunKind::kWall) out.walls->push_back(wall);
    return;
  }
  const Stretches stretches(wall, cfg.max_gap);
  std::vector<size_t> stretch_of(run.size());
  for (size_t k = 0; k < run.size(); ++k) {
    stretch_of[k] = stretches.of(stretches.along(pts[run[k]].head<2>().cast<double>()));
  }
  const std::vector<uint8_t> over = seenOver(pts, run, stretch_of, wall, stretches, view, cfg);
  const bool any_over = std::any_of(over.begin(), over.end(), [](uint8_t o) { return o != 0; });
  // A low surface is reported only when rays were seen over it: the wall under a row of wall
  // cabinets is low too, but the rays above it end on the cabinets.
  if (kind == RunKind::kLowSurface) {
    if (any_over) out.seen_over->push_back(wall);
    return;
  }
  if (!any_over) {
    out.walls->push_back(wall);
    return;
  }
  std::vector<std::vector<uint32_t>> by_stretch(stretches.count);
  for (size_t k = 0; k < run.size(); ++k) by_stretch[stretch_of[k]].push_back(run[k]);
  // Consecutive stretches that are all seen over or all not make one piece.
  std::vector<uint32_t> piece;
  for (size_t k = 0; k < stretches.count; ++k) {
    piece.insert(piece.end(), by_stretch[k].begin(), by_stretch[k].end());
    if (k + 1 < stretches.count && over[k + 1] == over[k]) continue;
    WallSegment w;
    const RunKind piece_kind =
        piece.empty() ? RunKind::kNone : makeWallSegment(pts, piece, cfg, view, &w);
    if (piece_kind == RunKind::kWall && !over[k]) {
      out.walls->push_back(w);
    } else if (piece_kind != RunKind::kNone) {
      out.seen_over->push_back(w);
    }
    piece.clear();
  }
}

// Splits the inliers of a vertical plane into runs along the wall separated by > max_gap and
// appends the runs that make valid segments. Runs and their extents come from the inliers off the
// plane's floor and ceiling lines (edge_band); those lines cross doorways, so their inliers only
// join a run they lie within.
void splitIntoWalls(const Points& pts, const std::vector<uint32_t>& inliers, const Plane& pl,
                    const WallExtractionConfig& cfg, const View& view, const RunOutput& out) {
  float z_lo = std::numeric_limits<float>::infinity(), z_hi = -z_lo;
  for (uint32_t i : inliers) {
    z_lo = std::min(z_lo, pts[i].z());
    z_hi = std::max(z_hi, pts[i].z());
  }
  const float band = static_cast<float>(cfg.edge_band);
  // A plane lower than a few bands (a kerb, a low box) has no body: every inlier counts.
  const bool use_band = band > 0.0f && z_hi - z_lo > 4.0f * band;
  const auto onEdge = [&](uint32_t i) {
    return use_band && (pts[i].z() < z_lo + band || pts[i].z() > z_hi - band);
  };
  const Eigen::Vector2f axis = wallAxis(pl.n).cast<float>();
  std::vector<std::pair<float, uint32_t>> body, edge;
  for (uint32_t i : inliers) {
    (onEdge(i) ? edge : body).emplace_back(axis.dot(pts[i].head<2>()), i);
  }
  std::sort(body.begin(), body.end());
  std::sort(edge.begin(), edge.end());
  // Edge inliers join a run only near its body's height: the ceiling line crossing the plane of
  // a desk front is no top of the desk (rings of a sparse LiDAR far away stay within this).
  constexpr float kEdgeReach = 1.0f;  // [m]
  size_t e = 0;                       // edge inliers are visited once, in order along the wall
  std::vector<uint32_t> run;
  float body_lo = std::numeric_limits<float>::infinity(), body_hi = -body_lo;
  for (size_t k = 0; k < body.size(); ++k) {
    run.push_back(body[k].second);
    body_lo = std::min(body_lo, pts[body[k].second].z());
    body_hi = std::max(body_hi, pts[body[k].second].z());
    const bool last = k + 1 == body.size() || body[k + 1].first - body[k].first > cfg.max_gap;
    if (!last) continue;
    const float t0 = body[k + 1 - run.size()].first, t1 = body[k].first;
    for (; e < edge.size() && edge[e].first <= t1; ++e) {
      const float z = pts[edge[e].second].z();
      if (edge[e].first >= t0 && z >= body_lo - kEdgeReach && z <= body_hi + kEdgeReach) {
        run.push_back(edge[e].second);
      }
    }
    body_lo = std::numeric_limits<float>::infinity();
    body_hi = -body_lo;
    appendWalls(pts, run, cfg, view, out);
    run.clear();
  }
}

WallSegment makeHorizontal(const Points& pts, const std::vector<uint32_t>& inliers, Plane pl,
                           const Eigen::Vector3d& viewpoint) {
  faceViewpoint(viewpoint, true, &pl);
  WallSegment h;
  h.normal = pl.n;
  h.d = pl.d;
  h.inliers = static_cast<uint32_t>(inliers.size());
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector3f hi = -lo;
  for (uint32_t i : inliers) {
    lo = lo.cwiseMin(pts[i]);
    hi = hi.cwiseMax(pts[i]);
  }
  h.endpoints[0] = lo.head<2>().cast<double>();
  h.endpoints[1] = hi.head<2>().cast<double>();
  h.z_min = lo.z();
  h.z_max = hi.z();
  return h;
}

// Sequential RANSAC state: the points not yet explained by a plane.
class PlaneSearch {
 public:
  PlaneSearch(const WallExtractionConfig& cfg, Scratch* scratch)
      : pts_(scratch->pts),
        cfg_(cfg),
        cells_(scratch->cells),
        active_(scratch->active),
        active_list_(scratch->active_list),
        sub_x_(scratch->sub_x),
        sub_y_(scratch->sub_y),
        sub_z_(scratch->sub_z),
        rng_(static_cast<uint32_t>(cfg.seed)) {
    buildSampleCells(pts_, cfg.sample_cell, scratch);
    active_.assign(pts_.size(), 1);
    active_list_.resize(pts_.size());
    for (size_t i = 0; i < pts_.size(); ++i) active_list_[i] = uint32_t(i);
  }

  size_t remaining() const { return active_list_.size(); }

  // Finds the best plane among the remaining points and its inliers; false if none.
  bool next(Plane* plane, std::vector<uint32_t>* inliers) {
    if (active_list_.size() < 3) return false;
    drawScoringSubsample();
    const float thr = static_cast<float>(cfg_.distance_threshold);
    Plane best;
    int best_score = 0;
    for (int it = 0; it < cfg_.ransac_iterations; ++it) {
      Plane hyp;
      if (!sampleHypothesis(&hyp)) continue;
      const int score = this->score(hyp);
      if (score > best_score) {
        best_score = score;
        best = hyp;
      }
    }
    if (best_score < 3) return false;
    collectInliers(pts_, active_list_, best, thr, inliers);
    for (int r = 0; r < cfg_.refine_iterations && inliers->size() >= 3; ++r) {
      best = fitPlane(pts_, *inliers, nullptr);
      collectInliers(pts_, active_list_, best, thr, inliers);
    }
    *plane = best;
    return true;
  }

  void remove(const std::vector<uint32_t>& idx) {
    for (uint32_t i : idx) active_[i] = 0;
    active_list_.erase(std::remove_if(active_list_.begin(), active_list_.end(),
                                      [&](uint32_t i) { return !active_[i]; }),
                       active_list_.end());
  }

 private:
  void drawScoringSubsample() {
    const size_t n = active_list_.size();
    const size_t m = std::min<size_t>(n, static_cast<size_t>(cfg_.score_subsample));
    sub_x_.resize(m);
    sub_y_.resize(m);
    sub_z_.resize(m);
    std::uniform_int_distribution<size_t> pick(0, n - 1);
    for (size_t k = 0; k < m; ++k) {
      const Eigen::Vector3f& p = pts_[active_list_[m == n ? k : pick(rng_)]];
      sub_x_[k] = p.x();
      sub_y_[k] = p.y();
      sub_z_[k] = p.z();
    }
  }

  int score(const Plane& hyp) const {
    const float nx = static_cast<float>(hyp.n.x()), ny = static_cast<float>(hyp.n.y());
    const float nz = static_cast<float>(hyp.n.z()), d = static_cast<float>(hyp.d);
    const float thr = static_cast<float>(cfg_.distance_threshold);
    const size_t m = sub_x_.size();
    int count = 0;
    for (size_t k = 0; k < m; ++k) {
      count += std::abs(nx * sub_x_[k] + ny * sub_y_[k] + nz * sub_z_[k] + d) < thr;
    }
    return count;
  }

  // Three remaining points from one sampling cell, or false after a few failed tries.
  bool sampleHypothesis(Plane* hyp) {
    std::uniform_int_distribution<size_t> pick(0, active_list_.size() - 1);
    const uint32_t a = active_list_[pick(rng_)];
    const uint32_t cell = cells_.cell_of[a];
    const uint32_t b0 = cells_.begin[cell], count = cells_.begin[cell + 1] - b0;
    if (count < 3) return false;
    std::uniform_int_distribution<uint32_t> in_cell(0, count - 1);
    uint32_t others[2];
    int found = 0;
    for (int tries = 0; tries < 8 && found < 2; ++tries) {
      const uint32_t c = cells_.members[b0 + in_cell(rng_)];
      if (c == a || !active_[c] || (found == 1 && c == others[0])) continue;
      others[found++] = c;
    }
    if (found < 2) return false;
    const Eigen::Vector3d pa = pts_[a].cast<double>();
    const Eigen::Vector3d cross =
        (pts_[others[0]].cast<double>() - pa).cross(pts_[others[1]].cast<double>() - pa);
    const double norm = cross.norm();
    if (norm < 1e-4) return false;  // (nearly) collinear sample
    hyp->n = cross / norm;
    hyp->d = -hyp->n.dot(pa);
    return true;
  }

  const Points& pts_;
  const WallExtractionConfig& cfg_;
  const SampleCells& cells_;
  std::vector<uint8_t>& active_;
  std::vector<uint32_t>& active_list_;
  std::vector<float>& sub_x_;
  std::vector<float>& sub_y_;
  std::vector<float>& sub_z_;
  std::mt19937 rng_;
};

bool byInliers(const WallSegment& a, const WallSegment& b) { return a.inliers > b.inliers; }

// Doors, cabinets and panels on a wall: a segment with same-facing walls of the same scan a little
// behind it (more than the inlier band, up to on_wall_max_depth) that were seen around or over it.
// Either one of them spans it, or it is flanked at both ends (within max_gap) by walls behind it
// at least as long together as it is: a closed door between the wall's pieces. A wall piece
// between two recessed doors is longer than the doors and stays. Such a surface is measured
// centimetres off the wall's plane and would pull the wall landmark and the poses tied to it.
std::vector<WallSegment> dropSurfacesOnWalls(std::vector<WallSegment> walls,
                                             const WallExtractionConfig& cfg) {
  if (cfg.on_wall_max_depth <= 0.0) return walls;
  const double min_cos = std::cos(cfg.vertical_tolerance_deg * M_PI / 180.0);
  std::vector<char> on_wall(walls.size(), 0);
  for (size_t i = 0; i < walls.size(); ++i) {
    const WallSegment& a = walls[i];
    const Eigen::Vector2d axis = wallAxis(a.normal);
    const double a0 = axis.dot(a.endpoints[0]), a1 = axis.dot(a.endpoints[1]);
    bool left = false, right = false;
    double flank_length = 0.0;
    for (size_t j = 0; j < walls.size() && !on_wall[i]; ++j) {
      const WallSegment& b = walls[j];
      if (j == i || a.normal.head<2>().dot(b.normal.head<2>()) < min_cos) continue;
      const double depth = planeDistance(b.normal, b.d, a.midpoint(), 0.5 * (a.z_min + a.z_max));
      if (depth <= cfg.distance_threshold || depth > cfg.on_wall_max_depth) continue;
      const double b0 = axis.dot(b.endpoints[0]), b1 = axis.dot(b.endpoints[1]);
      const double lo = std::min(b0, b1), hi = std::max(b0, b1);
      if (lo <= a0 && hi >= a1) on_wall[i] = 1;  // spans it
      const bool flanks_left = lo < a0 && hi >= a0 - cfg.max_gap && hi < a1;
      const bool flanks_right = hi > a1 && lo <= a1 + cfg.max_gap && lo > a0;
      left = left || flanks_left;
      right = right || flanks_right;
      if (flanks_left || flanks_right) flank_length += b.length();
    }
    if (left && right && flank_length >= a.length()) on_wall[i] = 1;
  }
  std::vector<WallSegment> kept;
  kept.reserve(walls.size());
  for (size_t i = 0; i < walls.size(); ++i) {
    if (!on_wall[i]) kept.push_back(walls[i]);
  }
  return kept;
}

}  // namespace

WallExtractor::WallExtractor(const WallExtractionConfig& config) : config_(config) {
  config_.validate();
}

WallExtractionResult WallExtractor::extract(const PointCloud& cloud_in_base,
                                            const Eigen::Vector3d& viewpoint) const {
  Stopwatch watch;
  WallExtractionResult result;
  result.input_points = cloud_in_base.size();
  thread_local Scratch scratch;
  cropAndDownsample(cloud_in_base, config_, &scratch);
  const Points& pts = scratch.pts;
  result.downsampled_points = pts.size();

  const View view = viewOf(pts, viewpoint);
  const double sin_vertical = std::sin(config_.vertical_tolerance_deg * M_PI / 180.0);
  const double cos_horizontal = std::cos(config_.horizontal_tolerance_deg * M_PI / 180.0);
  PlaneSearch search(config_, &scratch);
  Plane plane;
  std::vector<uint32_t>& inliers = scratch.inliers;
  while (result.planes_found < config_.max_planes &&
         search.remaining() >= static_cast<size_t>(config_.min_remaining_points) &&
         search.next(&plane, &inliers) &&
         inliers.size() >= static_cast<size_t>(config_.min_plane_inliers)) {
    ++result.planes_found;
    const double nz = std::abs(plane.n.z());
    if (nz <= sin_vertical) {
      splitIntoWalls(pts, inliers, plane, config_, view, {&result.walls, &result.seen_over});
    } else if (nz >= cos_horizontal &&
               inliers.size() >= static_cast<size_t>(config_.min_horizontal_inliers)) {
      result.horizontal.push_back(makeHorizontal(pts, inliers, plane, viewpoint));
    }
    search.remove(inliers);  // slanted planes and rejected fragments are explained away too
  }
  result.walls = dropSurfacesOnWalls(std::move(result.walls), config_);
  std::stable_sort(result.walls.begin(), result.walls.end(), byInliers);
  std::stable_sort(result.horizontal.begin(), result.horizontal.end(), byInliers);
  std::stable_sort(result.seen_over.begin(), result.seen_over.end(), byInliers);
  result.time_ms = watch.elapsedMs();
  return result;
}

WallExtractionResult WallExtractor::extractInFrame(const PointCloud& cloud_in_level,
                                                   const Pose3& T_base_level,
                                                   const Eigen::Vector3d& viewpoint_in_base) const {
  WallExtractionResult r = extract(cloud_in_level, T_base_level.inverse() * viewpoint_in_base);
  for (auto* list : {&r.walls, &r.seen_over, &r.horizontal}) {
    for (WallSegment& w : *list) w = transformWall(w, T_base_level);
  }
  return r;
}

}  // namespace tacs
