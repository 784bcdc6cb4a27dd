#include "tacs_graphs/relocalization/room_relocalizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kQuarter = kPi / 2.0;

std::vector<Eigen::Vector3d> finitePoints(const PointCloud& cloud, double voxel_m,
                                          size_t max_points) {
  const PointCloud thinned = voxelDownsample(cloud, voxel_m);
  std::vector<Eigen::Vector3d> points;
  points.reserve(thinned.size());
  for (const auto& p : thinned.points) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      points.emplace_back(p.x, p.y, p.z);
    }
  }
  if (max_points > 0 && points.size() > max_points) {  // every k-th: spread over the whole map
    const double step = static_cast<double>(points.size()) / max_points;
    std::vector<Eigen::Vector3d> kept;
    kept.reserve(max_points);
    for (size_t i = 0; i < max_points; ++i) kept.push_back(points[static_cast<size_t>(i * step)]);
    points.swap(kept);
  }
  return points;
}

/// Yaw of the dominant axes of a set of directions, modulo 90 deg (angles averaged four-fold).
double axesYaw(const std::vector<double>& angles) {
  double s = 0.0, c = 0.0;
  for (double a : angles) s += std::sin(4.0 * a), c += std::cos(4.0 * a);
  double yaw = 0.25 * std::atan2(s, c);
  if (yaw < 0.0) yaw += kQuarter;
  return yaw;
}

Pose3 planarPose(double x, double y, double yaw) {
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

int64_t cellKey(const Eigen::Vector2d& p, double cell) {
  const int64_t ix = static_cast<int64_t>(std::floor(p.x() / cell));
  const int64_t iy = static_cast<int64_t>(std::floor(p.y() / cell));
  return (ix << 32) ^ (iy & 0xffffffff);
}

/// Wall-like points of a prepared cloud (|normal z| <= max_normal_z). A plane-regularised
/// covariance is I - (1 - f) n n^T, so its zz entry gives the normal's z.
std::vector<uint32_t> wallPoints(const GicpCloud& cloud, double max_normal_z) {
  std::vector<uint32_t> out;
  const double f = kGicpPlaneVariance;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const double nz2 = (1.0 - cloud.covariances()[i](2, 2)) / (1.0 - f);
    if (nz2 <= max_normal_z * max_normal_z) out.push_back(static_cast<uint32_t>(i));
  }
  return out;
}

/// Yaw of the dominant wall axes of a cloud, modulo 90 deg, from its points' normals.
double wallAxesYaw(const GicpCloud& cloud, const std::vector<uint32_t>& walls) {
  std::vector<double> angles;
  angles.reserve(walls.size());
  for (uint32_t i : walls) {
    const Eigen::Matrix3d& c = cloud.covariances()[i];
    // n_x^2 and n_y^2 from the diagonal, the sign of n_x n_y from the off-diagonal entry.
    const double nx = std::sqrt(std::max(0.0, 1.0 - c(0, 0)));
    const double ny = std::sqrt(std::max(0.0, 1.0 - c(1, 1)));
    angles.push_back(std::atan2(c(0, 1) > 0.0 ? -ny : ny, nx));
  }
  return axesYaw(angles);
}

}  // namespace

/// The prior's wall points seen from above, in cells widened by one around each point: the
/// translation search of a session's map counts its wall cells that land on it.
struct RoomRelocalizer::WallGrid {
  double cell = 0.5;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  int width = 0, height = 0;
  std::vector<uint8_t> occupied;

  WallGrid(const std::vector<Eigen::Vector2d>& points, double cell_m) : cell(cell_m) {
    if (points.empty()) return;
    Eigen::Vector2d lo = points.front(), hi = lo;
    for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    origin = lo - Eigen::Vector2d::Constant(cell);
    width = static_cast<int>((hi.x() - origin.x()) / cell) + 2;
    height = static_cast<int>((hi.y() - origin.y()) / cell) + 2;
    occupied.assign(static_cast<size_t>(width) * height, 0);
    for (const auto& p : points) {
      const int x = static_cast<int>((p.x() - origin.x()) / cell);
      const int y = static_cast<int>((p.y() - origin.y()) / cell);
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) occupied[(y + dy) * width + (x + dx)] = 1;
      }
    }
  }
};

void RelocalizationConfig::validate() const {
  requireConfig(extent_tolerance_m >= 0.0, "relocalization.extent_tolerance_m", "must be >= 0");
  requireConfig(extent_tolerance_ratio >= 0.0, "relocalization.extent_tolerance_ratio",
                "must be >= 0");
  requireConfig(cloud_voxel_m > 0.0, "relocalization.cloud_voxel_m", "must be > 0");
  requireConfig(max_session_points >= 100, "relocalization.max_session_points", "must be >= 100");
  requireConfig(fine_gate_m > 0.0, "relocalization.fine_gate_m", "must be > 0");
  requireConfig(coarse_gate_m >= fine_gate_m, "relocalization.coarse_gate_m",
                "must be >= relocalization.fine_gate_m");
  requireConfig(fit_distance_m > 0.0, "relocalization.fit_distance_m", "must be > 0");
  requireConfig(fit_radius_m >= fit_distance_m, "relocalization.fit_radius_m",
                "must be >= relocalization.fit_distance_m");
  requireConfig(overlap_radius_m >= fit_radius_m, "relocalization.overlap_radius_m",
                "must be >= relocalization.fit_radius_m");
  requireConfig(min_overlap > 0.0 && min_overlap <= 1.0, "relocalization.min_overlap",
                "must be in (0, 1]");
  requireConfig(max_normal_z > 0.0 && max_normal_z <= 1.0, "relocalization.max_normal_z",
                "must be in (0, 1]");
  requireConfig(min_score > 0.0 && min_score <= 1.0, "relocalization.min_score",
                "must be in (0, 1]");
  requireConfig(min_misfit_ratio >= 1.0, "relocalization.min_misfit_ratio", "must be >= 1");
  requireConfig(misfit_floor > 0.0 && misfit_floor < 1.0, "relocalization.misfit_floor",
                "must be in (0, 1)");
  requireConfig(min_extra_misfits >= 0, "relocalization.min_extra_misfits", "must be >= 0");
  requireConfig(distinct_distance_m > 0.0, "relocalization.distinct_distance_m", "must be > 0");
  requireConfig(distinct_angle_deg > 0.0, "relocalization.distinct_angle_deg", "must be > 0");
  requireConfig(min_wall_points >= 1, "relocalization.min_wall_points", "must be >= 1");
  requireConfig(room_pair_overlap > 0.0 && room_pair_overlap <= 1.0,
                "relocalization.room_pair_overlap", "must be in (0, 1]");
  requireConfig(search_cell_m > 0.0, "relocalization.search_cell_m", "must be > 0");
  requireConfig(search_peaks_per_yaw >= 0, "relocalization.search_peaks_per_yaw", "must be >= 0");
  requireConfig(retry_distance_m >= 0.0, "relocalization.retry_distance_m", "must be >= 0");
}

RoomShape roomShape(const RoomNode& room, const SceneGraph& graph) {
  RoomShape shape;
  if (room.free_space.empty()) return shape;
  // Axes from the room's walls (their normals), else from the free space's principal axis.
  std::vector<double> angles;
  for (uint32_t id : room.wall_ids) {
    const auto it = graph.walls.find(id);
    if (it != graph.walls.end())
      angles.push_back(std::atan2(it->second.normal.y(), it->second.normal.x()));
  }
  if (angles.empty()) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : room.free_space) mean += p;
    mean /= static_cast<double>(room.free_space.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto& p : room.free_space) cov += (p - mean) * (p - mean).transpose();
    angles.push_back(0.5 * std::atan2(2.0 * cov(0, 1), cov(0, 0) - cov(1, 1)));
  }
  shape.yaw = axesYaw(angles);
  const Eigen::Rotation2Dd to_axes(-shape.yaw);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18), hi = -lo;
  for (const auto& p : room.free_space) {
    const Eigen::Vector2d q = to_axes * p;
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  shape.extent = hi - lo;
  shape.center = Eigen::Rotation2Dd(shape.yaw) * (0.5 * (lo + hi));
  shape.ok = true;
  return shape;
}

struct RoomRelocalizer::SessionCloud {
  GicpCloud::ConstPtr cloud;
  std::vector<uint32_t> wall_points;  // indices of the scored (wall-like) points
};

RoomRelocalizer::RoomRelocalizer(const PriorMap& prior, const RelocalizationConfig& config)
    : prior_(prior), config_(config) {
  config_.validate();
  prior_cloud_ = GicpCloud::build(finitePoints(prior.points, config_.cloud_voxel_m, 0),
                                  GicpConfig().k_neighbors, GicpConfig().num_threads);
  for (const auto& [id, room] : prior.graph.rooms) {
    const RoomShape shape = roomShape(room, prior.graph);
    if (shape.ok) prior_shapes_[id] = shape;
  }
  const std::vector<uint32_t> walls = wallPoints(*prior_cloud_, config_.max_normal_z);
  prior_yaw_ = wallAxesYaw(*prior_cloud_, walls);
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(walls.size());
  for (uint32_t i : walls) xy.push_back(prior_cloud_->points()[i].head<2>());
  prior_grid_ = std::make_unique<WallGrid>(xy, config_.search_cell_m);
}

RoomRelocalizer::~RoomRelocalizer() = default;

uint32_t RoomRelocalizer::priorRoomAt(const Eigen::Vector3d& p) const {
  uint32_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const auto& [id, room] : prior_.graph.rooms) {
    for (const auto& q : room.free_space) {
      const double d2 = (q - p.head<2>()).squaredNorm();
      if (d2 < best_d2) best_d2 = d2, best = id;
    }
  }
  return best;
}

std::vector<Pose3> RoomRelocalizer::searchTranslations(const SessionCloud& session) const {
  // For each of the four yaws that bring the session's wall axes onto the prior's, every shift
  // of the session's wall cells over the prior's grid is counted; the best shifts of each yaw
  // (apart by 2 m or more) are hypotheses.
  const WallGrid& grid = *prior_grid_;
  std::vector<Pose3> out;
  if (grid.width == 0 || session.wall_points.empty()) return out;
  const double session_yaw = wallAxesYaw(*session.cloud, session.wall_points);
  const int suppress = std::max(1, static_cast<int>(std::ceil(2.0 / grid.cell)));
  for (int k = 0; k < 4; ++k) {
    const double yaw = prior_yaw_ - session_yaw + k * kQuarter;
    const Eigen::Rotation2Dd R(yaw);
    std::vector<Eigen::Vector2d> rotated;
    rotated.reserve(session.wall_points.size());
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e18);
    for (uint32_t i : session.wall_points) {
      rotated.push_back(R * session.cloud->points()[i].head<2>());
      lo = lo.cwiseMin(rotated.back());
    }
    std::vector<std::pair<int, int>> cells;
    for (const auto& r : rotated) {
      cells.emplace_back(static_cast<int>((r.x() - lo.x()) / grid.cell),
                         static_cast<int>((r.y() - lo.y()) / grid.cell));
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    int sw = 0, sh = 0;
    for (const auto& [x, y] : cells) sw = std::max(sw, x + 1), sh = std::max(sh, y + 1);
    // Shifts that keep at least part of the session over the grid.
    const int ow = grid.width + sw, oh = grid.height + sh;
    std::vector<int> votes(static_cast<size_t>(ow) * oh, 0);
    for (int oy = 0; oy < oh; ++oy) {
      for (int ox = 0; ox < ow; ++ox) {
        int count = 0;
        for (const auto& [x, y] : cells) {
          const int gx = x + ox - sw, gy = y + oy - sh;
          if (gx >= 0 && gy >= 0 && gx < grid.width && gy < grid.height) {
            count += grid.occupied[gy * grid.width + gx];
          }
        }
        votes[oy * ow + ox] = count;
      }
    }
    for (int peak = 0; peak < config_.search_peaks_per_yaw; ++peak) {
      const auto best = std::max_element(votes.begin(), votes.end());
      if (*best <= 0) break;
      const int index = static_cast<int>(best - votes.begin());
      const int bx = index % ow, by = index / ow;
      // Session cell (x, y) lands on grid cell (x + bx - sw, y + by - sh): a session point r
      // (rotated) lies at r - lo + origin + (b - s) * cell in the prior's frame.
      const Eigen::Vector2d t = grid.origin - lo + grid.cell * Eigen::Vector2d(bx - sw, by - sh);
      out.push_back(planarPose(t.x(), t.y(), yaw));
      for (int y = std::max(0, by - suppress); y <= std::min(oh - 1, by + suppress); ++y) {
        for (int x = std::max(0, bx - suppress); x <= std::min(ow - 1, bx + suppress); ++x) {
          votes[y * ow + x] = 0;
        }
      }
    }
  }
  return out;
}

RoomRelocalizer::SessionCloud RoomRelocalizer::prepare(const PointCloud& session_points) const {
  SessionCloud s;
  s.cloud = GicpCloud::build(
      finitePoints(session_points, config_.cloud_voxel_m, config_.max_session_points),
      GicpConfig().k_neighbors, GicpConfig().num_threads);
  s.wall_points = wallPoints(*s.cloud, config_.max_normal_z);
  return s;
}

double RoomRelocalizer::score(const SessionCloud& session, const Pose3& T) const {
  // Session points where the prior has no point within overlap_radius_m lie where the prior
  // never looked (a part of the building the first session did not visit): they neither fit
  // nor misfit. The overlap counts as at least min_overlap of the points, so that a place that
  // puts most of the session outside the prior is not judged by a few points.
  // A point fits when it lies on the plane of its nearest prior point (within fit_distance_m of
  // it, that point no farther than fit_radius_m): maps voxelised at 0.2 m leave gaps of that
  // size between a surface's points.
  if (session.wall_points.empty()) return 0.0;
  const double fit_sq = config_.fit_distance_m * config_.fit_distance_m;
  const double radius_sq = config_.fit_radius_m * config_.fit_radius_m;
  const double overlap_sq = config_.overlap_radius_m * config_.overlap_radius_m;
  size_t fit = 0, overlap = 0;
  for (uint32_t i : session.wall_points) {
    const Eigen::Vector3d p = T * session.cloud->points()[i];
    double d2 = 0.0;
    const int64_t j = prior_cloud_->nearest(p, overlap_sq, &d2);
    if (j < 0) continue;
    ++overlap;
    if (d2 > radius_sq) continue;
    // The prior covariance is I - (1 - f) n n^T: (I - C) / (1 - f) = n n^T.
    const Eigen::Vector3d d = p - prior_cloud_->points()[j];
    const Eigen::Matrix3d& C = prior_cloud_->covariances()[j];
    const double plane_sq = d.dot(d - C * d) / (1.0 - kGicpPlaneVariance);
    if (plane_sq <= fit_sq) ++fit;
  }
  const double counted =
      std::max(static_cast<double>(overlap),
               config_.min_overlap * static_cast<double>(session.wall_points.size()));
  return static_cast<double>(fit) / counted;
}

PlaceHypothesis RoomRelocalizer::verify(const SessionCloud& session, const Pose3& guess,
                                        const std::vector<double>& gates) const {
  PlaceHypothesis h;
  h.T_prior_session = guess;
  for (double gate : gates) {
    GicpConfig gicp_config;
    gicp_config.max_correspondence_distance_m = gate;
    Gicp gicp(gicp_config);
    gicp.setTarget(prior_cloud_);
    gicp.setSource(session.cloud);
    h.T_prior_session = gicp.align(h.T_prior_session).T_target_source;
  }
  h.score = score(session, h.T_prior_session);
  return h;
}

bool RoomRelocalizer::distinct(const Pose3& a, const Pose3& b) const {
  const Pose3 d = a.inverse() * b;
  return d.translation().norm() > config_.distinct_distance_m ||
         rotationAngleDeg(d) > config_.distinct_angle_deg;
}

std::vector<double> RoomRelocalizer::gates() const {
  return {config_.coarse_gate_m, 0.5 * (config_.coarse_gate_m + config_.fine_gate_m),
          config_.fine_gate_m};
}

std::vector<PlaceHypothesis> RoomRelocalizer::shapeHypotheses(const SessionCloud& cloud,
                                                              const RoomShape& shape) const {
  const auto fits = [&](double a, double b) {
    return std::abs(a - b) <=
           std::max(config_.extent_tolerance_m, config_.extent_tolerance_ratio * std::max(a, b));
  };
  std::vector<PlaceHypothesis> verified;
  for (const auto& [prior_id, prior_shape] : prior_shapes_) {
    for (int k = 0; k < 4; ++k) {
      const bool swapped = k % 2 == 1;
      const Eigen::Vector2d extent =
          swapped ? Eigen::Vector2d(shape.extent.y(), shape.extent.x()) : shape.extent;
      if (!fits(extent.x(), prior_shape.extent.x()) || !fits(extent.y(), prior_shape.extent.y())) {
        continue;
      }
      const double yaw = prior_shape.yaw - shape.yaw + k * kQuarter;
      const Eigen::Vector2d t = prior_shape.center - Eigen::Rotation2Dd(yaw) * shape.center;
      PlaceHypothesis h = verify(cloud, planarPose(t.x(), t.y(), yaw), gates());
      h.prior_room = prior_id;
      verified.push_back(h);
    }
  }
  return verified;
}

RelocalizationAttempt RoomRelocalizer::decide(const SessionCloud& cloud,
                                              std::vector<PlaceHypothesis> verified,
                                              const Eigen::Vector3d& anchor,
                                              RelocalizationAttempt attempt) const {
  // Rooms are cut where the robot happened to enter and leave them (a corridor ring is split
  // elsewhere by each session), so the shape hypotheses may all miss: the translation search
  // adds places found from the whole map's walls.
  for (const Pose3& guess : searchTranslations(cloud)) {
    PlaceHypothesis h = verify(cloud, guess, gates());
    h.prior_room = priorRoomAt(h.T_prior_session * anchor);
    verified.push_back(h);
  }
  attempt.hypotheses = static_cast<int>(verified.size());
  attempt.wall_points = cloud.wall_points.size();
  if (verified.empty()) {
    attempt.reason = "no place in the prior fits the session's walls";
    return attempt;
  }
  std::sort(verified.begin(), verified.end(),
            [](const PlaceHypothesis& a, const PlaceHypothesis& b) { return a.score > b.score; });
  attempt.best = verified.front();
  for (size_t i = 1; i < verified.size(); ++i) {
    if (distinct(verified.front().T_prior_session, verified[i].T_prior_session)) {
      attempt.runner_up_score = verified[i].score;
      break;
    }
  }
  const double best_misfit = std::max(1.0 - attempt.best.score, config_.misfit_floor);
  const double runner_up_misfit = 1.0 - attempt.runner_up_score;
  const double extra_misfits =
      (attempt.best.score - attempt.runner_up_score) * static_cast<double>(attempt.wall_points);
  attempt.localized = attempt.best.score >= config_.min_score &&
                      runner_up_misfit >= config_.min_misfit_ratio * best_misfit &&
                      extra_misfits >= config_.min_extra_misfits;
  attempt.rejected = attempt.hypotheses - (attempt.localized ? 1 : 0);
  if (!attempt.localized) {
    attempt.reason = attempt.best.score < config_.min_score ? "no hypothesis fits the prior's map"
                                                            : "two distinct places fit alike";
  }
  return attempt;
}

RelocalizationAttempt RoomRelocalizer::tryRoom(const SceneGraph& session,
                                               const PointCloud& session_points,
                                               uint32_t room_id) const {
  Stopwatch watch;
  RelocalizationAttempt attempt;
  attempt.session_room = room_id;
  const auto room = session.rooms.find(room_id);
  const RoomShape shape =
      room == session.rooms.end() ? RoomShape() : roomShape(room->second, session);
  if (room == session.rooms.end()) {
    attempt.reason = "no such room in the session";
  } else if (!shape.ok) {
    attempt.reason = "the room has no free space";
  } else {
    const SessionCloud cloud = prepare(session_points);
    if (cloud.wall_points.size() < static_cast<size_t>(config_.min_wall_points)) {
      attempt.reason = "the session's map holds too few wall points yet";
    } else {
      attempt = decide(cloud, shapeHypotheses(cloud, shape), room->second.center, attempt);
    }
  }
  attempt.time_ms = watch.elapsedMs();
  return attempt;
}

RelocalizationAttempt RoomRelocalizer::tryMap(const PointCloud& session_points,
                                              const Eigen::Vector3d& where) const {
  Stopwatch watch;
  RelocalizationAttempt attempt;
  const SessionCloud cloud = prepare(session_points);
  if (cloud.wall_points.size() < static_cast<size_t>(config_.min_wall_points)) {
    attempt.reason = "the session's map holds too few wall points yet";
  } else {
    attempt = decide(cloud, {}, where, attempt);
  }
  attempt.time_ms = watch.elapsedMs();
  return attempt;
}

PlaceHypothesis RoomRelocalizer::refine(const PointCloud& session_points,
                                        const Pose3& T_prior_session) const {
  const SessionCloud cloud = prepare(session_points);
  return verify(cloud, T_prior_session,
                {0.5 * (config_.coarse_gate_m + config_.fine_gate_m), config_.fine_gate_m});
}

std::map<uint32_t, uint32_t> pairRooms(const SceneGraph& session, const SceneGraph& prior,
                                       const Pose3& T_prior_session, double min_overlap) {
  // The prior's free space in cells of 0.5 m, each cell widened by one around it (free-space
  // nodes lie about a cell apart).
  constexpr double kCell = 0.5;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells;
  for (const auto& [id, room] : prior.rooms) {
    for (const auto& p : room.free_space) {
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          auto& ids = cells[cellKey(p + kCell * Eigen::Vector2d(dx, dy), kCell)];
          if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
        }
      }
    }
  }
  const Eigen::Rotation2Dd yaw(
      std::atan2(T_prior_session.linear()(1, 0), T_prior_session.linear()(0, 0)));
  const Eigen::Vector2d shift = T_prior_session.translation().head<2>();
  std::map<uint32_t, uint32_t> pairs;
  for (const auto& [id, room] : session.rooms) {
    if (room.free_space.empty()) continue;
    std::map<uint32_t, size_t> inside;
    for (const auto& p : room.free_space) {
      const auto it = cells.find(cellKey(yaw * p + shift, kCell));
      if (it == cells.end()) continue;
      for (uint32_t prior_id : it->second) ++inside[prior_id];
    }
    const auto best =
        std::max_element(inside.begin(), inside.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (best != inside.end() &&
        best->second >= min_overlap * static_cast<double>(room.free_space.size())) {
      pairs[id] = best->first;
    }
  }
  return pairs;
}

}  // namespace tacs
