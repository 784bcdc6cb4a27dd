#include "tacs_graphs/backend/factor_graph.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>

#include "tacs_graphs/backend/analytic_costs.h"
#include "tacs_graphs/backend/factors.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/timing.h"

namespace tacs {
namespace {

// A cost made for one solve: owned by `costs`, which outlives the problem that borrows it.
ceres::CostFunction* keep(FactorGraph::SolveCosts* costs, ceres::CostFunction* cost) {
  costs->emplace_back(cost);
  return cost;
}

}  // namespace

void BackendConfig::validate() const {
  for (const auto& [name, value] : {std::pair{"wall_sigma_normal", wall_sigma_normal},
                                    {"wall_sigma_d_m", wall_sigma_d},
                                    {"wall_huber", wall_huber},
                                    {"loop_huber", loop_huber},
                                    {"room_sigma_m", room_sigma},
                                    {"corridor_anchor_sigma_m", corridor_anchor_sigma},
                                    {"wall_merge_sigma_theta_rad", wall_merge_sigma_theta},
                                    {"wall_merge_sigma_d_m", wall_merge_sigma_d}}) {
    requireConfig(value > 0, std::string("backend.") + name, "must be > 0");
  }
  requireConfig(anchor_tilt_sigma >= 0, "backend.anchor_tilt_sigma_rad", "must be >= 0");
  requireConfig(max_iterations >= 1, "backend.max_iterations", "must be >= 1");
  requireConfig(num_threads >= 1, "backend.num_threads", "must be >= 1");
  requireConfig(optimize_every_keyframes >= 1, "backend.optimize_every_keyframes", "must be >= 1");
  requireConfig(window_keyframes >= 0, "backend.window_keyframes", "must be >= 0 (0: off)");
  requireConfig(full_solve_fraction > 0 && full_solve_fraction <= 1, "backend.full_solve_fraction",
                "must be in (0, 1]");
}

size_t optimizationWindow(const BackendConfig& config, size_t keyframes,
                          size_t keyframes_since_full_solve, bool loop_pending) {
  const size_t window = static_cast<size_t>(config.window_keyframes);
  if (window == 0 || loop_pending) return 0;
  const double due = std::max(static_cast<double>(window), config.full_solve_fraction * keyframes);
  return static_cast<double>(keyframes_since_full_solve) >= due ? 0 : window;
}

WallPlane WallPlane::fromNormalD(const Eigen::Vector3d& normal, double d) {
  const Eigen::Vector2d horizontal = normal.head<2>();
  const double norm = horizontal.norm();
  if (norm < 1e-6) throw std::invalid_argument("WallPlane: a horizontal plane is not a wall");
  // n . p + d = 0 with a unit 3D normal; rescale so the horizontal normal is unit.
  return {std::atan2(horizontal.y(), horizontal.x()), d / norm};
}

FactorGraph::FactorGraph(const BackendConfig& config) : config_(config) { config_.validate(); }

void FactorGraph::addKeyframe(uint32_t id, const Pose3& T_map_base) {
  const Eigen::Quaterniond q(T_map_base.rotation());
  const Eigen::Vector3d t = T_map_base.translation();
  keyframes_[id] = {{t.x(), t.y(), t.z()}, {q.x(), q.y(), q.z(), q.w()}};
  if (!anchor_keyframe_) {
    anchor_keyframe_ = id;
    anchor_orientation_ = q;
  }
}

void FactorGraph::addRelativePose(uint32_t from, uint32_t to, const Pose3& T_from_to,
                                  const Matrix6d& information, bool robust) {
  if (!hasKeyframe(from) || !hasKeyframe(to)) {
    throw std::invalid_argument("FactorGraph: relative pose between unknown keyframes");
  }
  const Eigen::LLT<Matrix6d> llt(information);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("FactorGraph: information matrix is not positive definite");
  }
  pose_edges_.push_back(
      {from, to, std::make_shared<RelativePoseCost>(T_from_to, llt.matrixU()), robust});
}

void FactorGraph::addWall(uint32_t id, const WallPlane& plane) {
  walls_[id] = {plane.theta, plane.d};
}

void FactorGraph::addWallObservation(uint32_t keyframe, uint32_t wall,
                                     const Eigen::Vector3d& n_base, double d_base) {
  if (!hasKeyframe(keyframe) || !hasWall(wall)) {
    throw std::invalid_argument("FactorGraph: wall observation of an unknown keyframe or wall");
  }
  const auto [first, added] = first_observer_.emplace(wall, keyframe);
  if (!added) first->second = std::min(first->second, keyframe);
  wall_observations_.push_back(
      {keyframe, wall,
       std::make_shared<WallObservationCost>(n_base, d_base, config_.wall_sigma_normal,
                                             config_.wall_sigma_d)});
}

void FactorGraph::mergeWalls(uint32_t kept, uint32_t removed) {
  if (kept == removed || !hasWall(kept) || !hasWall(removed)) return;
  for (auto& o : wall_observations_) {
    if (o.wall == removed) o.wall = kept;
  }
  for (auto& [a, b] : wall_to_wall_) {
    if (a == removed) a = kept;
    if (b == removed) b = kept;
  }
  for (auto& [id, room] : rooms_) {
    for (auto& [a, b] : room.wall_pairs) {
      if (a == removed) a = kept;
      if (b == removed) b = kept;
    }
  }
  const auto gone = first_observer_.find(removed);
  if (gone != first_observer_.end()) {
    const auto [kept_first, added] = first_observer_.emplace(kept, gone->second);
    if (!added) kept_first->second = std::min(kept_first->second, gone->second);
    first_observer_.erase(gone);
  }
  walls_.erase(removed);
}

void FactorGraph::addWallToWall(uint32_t wall_a, uint32_t wall_b) {
  if (!hasWall(wall_a) || !hasWall(wall_b)) {
    throw std::invalid_argument("FactorGraph: wall-to-wall edge between unknown walls");
  }
  wall_to_wall_.emplace_back(wall_a, wall_b);
}

void FactorGraph::setRoom(uint32_t id, const Eigen::Vector2d& center,
                          const std::vector<std::pair<uint32_t, uint32_t>>& wall_pairs,
                          const std::optional<Eigen::Vector2d>& corridor_anchor) {
  for (const auto& [a, b] : wall_pairs) {
    if (!hasWall(a) || !hasWall(b))
      throw std::invalid_argument("FactorGraph: room on unknown wall");
  }
  rooms_[id] = {{center.x(), center.y()}, wall_pairs, corridor_anchor};
}

void FactorGraph::removeRoom(uint32_t id) { rooms_.erase(id); }

FactorGraph::Scope FactorGraph::windowScope(size_t window_keyframes) const {
  Scope scope;
  if (window_keyframes == 0 || window_keyframes >= keyframes_.size()) return scope;  // all free
  scope.whole = false;
  auto it = keyframes_.end();
  std::advance(it, -static_cast<std::ptrdiff_t>(window_keyframes));
  scope.first_free_keyframe = it->first;
  for (const auto& [wall, keyframe] : first_observer_) {
    if (!scope.freeKeyframe(keyframe)) scope.held_walls.insert(wall);
  }
  return scope;
}

void FactorGraph::useKeyframe(ceres::Problem* problem, ceres::Manifold* quaternion,
                              const Scope& scope, uint32_t id) {
  auto& kf = keyframes_.at(id);
  if (problem->HasParameterBlock(kf.t.data())) return;
  problem->AddParameterBlock(kf.t.data(), 3);
  problem->AddParameterBlock(kf.q.data(), 4, quaternion);
  if (!scope.freeKeyframe(id)) {
    problem->SetParameterBlockConstant(kf.t.data());
    problem->SetParameterBlockConstant(kf.q.data());
  }
}

double* FactorGraph::useWall(ceres::Problem* problem, const Scope& scope, uint32_t id) {
  double* plane = walls_.at(id).data();
  if (!problem->HasParameterBlock(plane)) {
    problem->AddParameterBlock(plane, 2);
    if (!scope.freeWall(id)) problem->SetParameterBlockConstant(plane);
  }
  return plane;
}

void FactorGraph::addKeyframeBlocks(ceres::Problem* problem, ceres::Manifold* quaternion,
                                    const Scope& scope, SolveCosts* costs) {
  for (const auto& [id, kf] : keyframes_) {
    if (scope.freeKeyframe(id)) useKeyframe(problem, quaternion, scope, id);
  }
  if (!anchor_keyframe_ || !scope.freeKeyframe(*anchor_keyframe_)) return;
  auto& anchor = keyframes_.at(*anchor_keyframe_);
  problem->SetParameterBlockConstant(anchor.t.data());
  if (config_.anchor_tilt_sigma > 0.0) {
    // Yaw is the gauge: held by a prior far tighter than anything that could pull on it.
    constexpr double kYawSigma = 1e-6;
    auto* cost = keep(costs, new ceres::AutoDiffCostFunction<AnchorOrientationFactor, 3, 4>(
                                 new AnchorOrientationFactor(
                                     anchor_orientation_, config_.anchor_tilt_sigma, kYawSigma)));
    problem->AddResidualBlock(cost, nullptr, anchor.q.data());
  } else {
    problem->SetParameterBlockConstant(anchor.q.data());
  }
}

void FactorGraph::addPoseAndWallFactors(ceres::Problem* problem, ceres::Manifold* quaternion,
                                        const Scope& scope, ceres::LossFunction* loop_loss,
                                        ceres::LossFunction* wall_loss) {
  for (const auto& e : pose_edges_) {
    if (!scope.freeKeyframe(e.from) && !scope.freeKeyframe(e.to)) continue;
    useKeyframe(problem, quaternion, scope, e.from);
    useKeyframe(problem, quaternion, scope, e.to);
    auto& a = keyframes_.at(e.from);
    auto& b = keyframes_.at(e.to);
    problem->AddResidualBlock(e.cost.get(), e.robust ? loop_loss : nullptr, a.t.data(), a.q.data(),
                              b.t.data(), b.q.data());
  }
  for (const auto& o : wall_observations_) {
    if (!scope.freeKeyframe(o.keyframe)) continue;
    auto& kf = keyframes_.at(o.keyframe);
    problem->AddResidualBlock(o.cost.get(), wall_loss, kf.t.data(), kf.q.data(),
                              useWall(problem, scope, o.wall));
  }
}

void FactorGraph::addRoomFactors(ceres::Problem* problem, const Scope& scope, SolveCosts* costs) {
  const auto touchesFree = [&](const Room& room) {
    for (const auto& [a, b] : room.wall_pairs) {
      if (scope.freeWall(a) || scope.freeWall(b)) return true;
    }
    return scope.whole;
  };
  for (auto& [id, room] : rooms_) {
    if (!touchesFree(room)) continue;  // all its walls held: the room stays where it is
    for (const auto& [a, b] : room.wall_pairs) {
      if (a == b) continue;  // both sides merged into one wall: no constraint left
      auto* cost = keep(costs, new ceres::AutoDiffCostFunction<RoomPairFactor, 1, 2, 2, 2>(
                                   new RoomPairFactor(config_.room_sigma)));
      problem->AddResidualBlock(cost, nullptr, room.center.data(), useWall(problem, scope, a),
                                useWall(problem, scope, b));
    }
    if (room.corridor_anchor && !room.wall_pairs.empty()) {
      auto* cost =
          keep(costs,
               new ceres::AutoDiffCostFunction<CorridorAnchorFactor, 1, 2, 2>(
                   new CorridorAnchorFactor(*room.corridor_anchor, config_.corridor_anchor_sigma)));
      problem->AddResidualBlock(cost, nullptr, room.center.data(),
                                useWall(problem, scope, room.wall_pairs.front().first));
    }
    if (room.wall_pairs.empty()) problem->AddParameterBlock(room.center.data(), 2);
  }
  for (const auto& [a, b] : wall_to_wall_) {
    if (a == b || (!scope.freeWall(a) && !scope.freeWall(b))) continue;
    auto* cost =
        keep(costs, new ceres::AutoDiffCostFunction<WallToWallFactor, 2, 2, 2>(new WallToWallFactor(
                        config_.wall_merge_sigma_theta, config_.wall_merge_sigma_d)));
    problem->AddResidualBlock(cost, nullptr, useWall(problem, scope, a),
                              useWall(problem, scope, b));
  }
}

OptimizationReport FactorGraph::optimize(size_t window_keyframes) {
  OptimizationReport report;
  Stopwatch watch;
  const ThreadCpuStopwatch cpu;
  const Scope scope = windowScope(window_keyframes);
  report.window = !scope.whole;
  // The problem borrows everything: the stored costs, and what this solve makes (declared first,
  // so it outlives the problem).
  SolveCosts costs;
  ceres::EigenQuaternionManifold quaternion_manifold;
  ceres::HuberLoss loop_loss(config_.loop_huber), wall_loss(config_.wall_huber);
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  addKeyframeBlocks(&problem, &quaternion_manifold, scope, &costs);
  addPoseAndWallFactors(&problem, &quaternion_manifold, scope, &loop_loss, &wall_loss);
  addRoomFactors(&problem, scope, &costs);
  report.residual_blocks = static_cast<size_t>(problem.NumResidualBlocks());
  if (report.residual_blocks == 0) {
    report.usable = true;
    report.time_ms = watch.elapsedMs();
    report.cpu_ms = cpu.elapsedMs();
    return report;
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = config_.max_iterations;
  if (config_.trust_region == TrustRegion::kDogleg)
    options.trust_region_strategy_type = ceres::DOGLEG;
  options.num_threads = config_.num_threads;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  report.usable = summary.IsSolutionUsable();
  report.iterations = static_cast<int>(summary.iterations.size());
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  report.time_ms = watch.elapsedMs();
  report.cpu_ms = cpu.elapsedMs();
  return report;
}

Eigen::Vector3d FactorGraph::keyframePosition(uint32_t id) const {
  const auto& kf = keyframes_.at(id);
  return Eigen::Vector3d(kf.t[0], kf.t[1], kf.t[2]);
}

Pose3 FactorGraph::keyframePose(uint32_t id) const {
  const auto& kf = keyframes_.at(id);
  Pose3 pose = Pose3::Identity();
  pose.linear() =
      Eigen::Quaterniond(kf.q[3], kf.q[0], kf.q[1], kf.q[2]).normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(kf.t[0], kf.t[1], kf.t[2]);
  return pose;
}

WallPlane FactorGraph::wall(uint32_t id) const {
  const auto& w = walls_.at(id);
  return {w[0], w[1]};
}

Eigen::Vector2d FactorGraph::roomCenter(uint32_t id) const {
  const auto& r = rooms_.at(id);
  return {r.center[0], r.center[1]};
}

}  // namespace tacs
