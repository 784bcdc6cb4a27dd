// The hierarchical factor graph (paper Sec. III, Fig. 1): keyframe poses, wall planes and room
// centres as Ceres parameter blocks; odometry, loop, keyframe-wall, room and wall-to-wall factors.
// The problem is rebuilt from the stored measurements at every optimisation, so walls and rooms can
// be merged or removed between optimisations without bookkeeping inside Ceres; a window solve
// builds only the part around the newest keyframes, so its cost does not grow with the graph. The
// cost functions of odometry, loop and keyframe-wall factors (nearly all residuals) are made once,
// with their measurement, and lent to each problem.
#pragma once

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/types.h"

namespace ceres {
class CostFunction;
class LossFunction;
class Manifold;
class Problem;
}  // namespace ceres

namespace tacs {

/// backend.trust_region: Levenberg-Marquardt, or Powell's dogleg (on large pose graphs it often
/// needs fewer iterations, see bench_backend --trust-region).
enum class TrustRegion { kLevenbergMarquardt, kDogleg };
template <>
struct EnumNames<TrustRegion> {
  static constexpr std::array<std::pair<TrustRegion, const char*>, 2> kNames{
      {{TrustRegion::kLevenbergMarquardt, "levenberg_marquardt"},
       {TrustRegion::kDogleg, "dogleg"}}};
};

struct BackendConfig {
  double wall_sigma_normal = 0.05;       // keyframe-wall factor, normal components [-]
  double wall_sigma_d = 0.05;            // keyframe-wall factor, plane distance [m]
  double wall_huber = 1.0;               // robust loss on whitened keyframe-wall residuals [-]
  double loop_huber = 1.0;               // robust loss on whitened loop residuals [-]
  double room_sigma = 0.1;               // room/corridor centre midway between facing walls [m]
  double corridor_anchor_sigma = 1.0;    // corridor centre along its walls [m]
  double wall_merge_sigma_theta = 0.02;  // wall-to-wall edge, angle [rad]
  double wall_merge_sigma_d = 0.05;      // wall-to-wall edge, distance [m]
  int max_iterations = 20;               // trust-region iterations per optimisation
  TrustRegion trust_region = TrustRegion::kDogleg;
  int num_threads = 1;               // Ceres threads (the other core runs the front end)
  int optimize_every_keyframes = 1;  // optimise after this many new keyframes (and on each loop)
  // Window solves: between full solves, only the newest window_keyframes keyframes and the walls
  // no older keyframe has seen move; the rest is held (0: every optimisation is a full solve;
  // results/backend_window.md: the same ATE, rooms and loops as full solves on every world).
  // A full solve follows each loop closure, the end of a run, and every time the keyframes added
  // since the last one reach full_solve_fraction of the graph, so the cost per keyframe stays
  // bounded as the graph grows.
  int window_keyframes = 30;
  double full_solve_fraction = 0.25;
  // Roll and pitch of the first keyframe, which anchors the map: 0 holds them as measured; > 0
  // lets the vertical walls level the map within this prior [rad].
  double anchor_tilt_sigma = 0.05;

  template <class V>
  void visit(V& v) {
    v("wall_sigma_normal", wall_sigma_normal);
    v("wall_sigma_d_m", wall_sigma_d);
    v("wall_huber", wall_huber);
    v("loop_huber", loop_huber);
    v("room_sigma_m", room_sigma);
    v("corridor_anchor_sigma_m", corridor_anchor_sigma);
    v("wall_merge_sigma_theta_rad", wall_merge_sigma_theta);
    v("wall_merge_sigma_d_m", wall_merge_sigma_d);
    v("anchor_tilt_sigma_rad", anchor_tilt_sigma);
    v("max_iterations", max_iterations);
    v("trust_region", trust_region);
    v("num_threads", num_threads);
    v("optimize_every_keyframes", optimize_every_keyframes);
    v("window_keyframes", window_keyframes);
    v("full_solve_fraction", full_solve_fraction);
  }
  void validate() const;
};

struct OptimizationReport {
  bool usable = false;  // Ceres returned a usable solution
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double time_ms = 0.0;  // wall time
  double cpu_ms = 0.0;   // CPU time of the optimising thread (time_ms less waiting for a core)
  size_t residual_blocks = 0;
  bool window = false;  // a window solve (BackendConfig::window_keyframes), not a full one
};

/// The window of the optimisation due now (FactorGraph::optimize): 0, a full solve, after a loop
/// closure, when window solves are off, or once the keyframes added since the last full solve
/// reach full_solve_fraction of the graph (and at least the window); else window_keyframes.
size_t optimizationWindow(const BackendConfig& config, size_t keyframes,
                          size_t keyframes_since_full_solve, bool loop_pending);

/// A vertical wall plane n . p + d = 0, n = (cos theta, sin theta, 0).
struct WallPlane {
  double theta = 0.0;
  double d = 0.0;
  Eigen::Vector3d normal() const { return {std::cos(theta), std::sin(theta), 0.0}; }
  /// From any plane: the normal is projected onto the horizontal plane (walls are vertical).
  static WallPlane fromNormalD(const Eigen::Vector3d& normal, double d);
};

class FactorGraph {
 public:
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  /// The costs one optimisation makes and its problem borrows (room layer, anchor prior).
  using SolveCosts = std::vector<std::unique_ptr<ceres::CostFunction>>;
  explicit FactorGraph(const BackendConfig& config);

  /// The first keyframe added anchors the map frame: its position and yaw are held, its roll and
  /// pitch too unless anchor_tilt_sigma > 0.
  void addKeyframe(uint32_t id, const Pose3& T_map_base);
  bool hasKeyframe(uint32_t id) const { return keyframes_.count(id) > 0; }
  /// Odometry (robust = false) or loop closure (robust = true) edge: T_from_to measured.
  void addRelativePose(uint32_t from, uint32_t to, const Pose3& T_from_to,
                       const Matrix6d& information, bool robust);

  void addWall(uint32_t id, const WallPlane& plane);
  bool hasWall(uint32_t id) const { return walls_.count(id) > 0; }
  /// The wall seen from a keyframe as (n_base, d_base) in the base frame.
  void addWallObservation(uint32_t keyframe, uint32_t wall, const Eigen::Vector3d& n_base,
                          double d_base);
  /// Removes wall `removed`; its observations and edges move to `kept`.
  void mergeWalls(uint32_t kept, uint32_t removed);
  /// Wall-to-wall edge of room merging (paper eq. 4).
  void addWallToWall(uint32_t wall_a, uint32_t wall_b);

  /// Adds or replaces a room: facing wall pairs (two for a room, one for a corridor) and, for a
  /// corridor, the free-space centre that anchors it along its walls.
  void setRoom(uint32_t id, const Eigen::Vector2d& center,
               const std::vector<std::pair<uint32_t, uint32_t>>& wall_pairs,
               const std::optional<Eigen::Vector2d>& corridor_anchor);
  void removeRoom(uint32_t id);

  /// Optimises the whole graph (window_keyframes = 0 or at least the graph's size), or only the
  /// newest window_keyframes keyframes and the walls no older keyframe has seen, holding the
  /// rest; factors between held blocks are left out.
  OptimizationReport optimize(size_t window_keyframes = 0);

  Pose3 keyframePose(uint32_t id) const;
  Eigen::Vector3d keyframePosition(uint32_t id) const;
  WallPlane wall(uint32_t id) const;
  Eigen::Vector2d roomCenter(uint32_t id) const;
  size_t keyframeCount() const { return keyframes_.size(); }
  size_t wallCount() const { return walls_.size(); }
  size_t roomCount() const { return rooms_.size(); }

 private:
  // Which blocks an optimisation moves: everything (a full solve), or the newest keyframes and
  // the walls no older keyframe has seen (a window solve).
  struct Scope {
    bool whole = true;
    uint32_t first_free_keyframe = 0;
    std::set<uint32_t> held_walls;
    bool freeKeyframe(uint32_t id) const { return whole || id >= first_free_keyframe; }
    bool freeWall(uint32_t id) const { return whole || held_walls.count(id) == 0; }
  };
  Scope windowScope(size_t window_keyframes) const;
  // The steps of optimize(): parameter blocks and gauge, then the factors by layer. A held block
  // enters the problem, constant, only when a factor of a free one needs it.
  void useKeyframe(ceres::Problem* problem, ceres::Manifold* quaternion, const Scope& scope,
                   uint32_t id);
  double* useWall(ceres::Problem* problem, const Scope& scope, uint32_t id);
  void addKeyframeBlocks(ceres::Problem* problem, ceres::Manifold* quaternion, const Scope& scope,
                         SolveCosts* costs);
  void addPoseAndWallFactors(ceres::Problem* problem, ceres::Manifold* quaternion,
                             const Scope& scope, ceres::LossFunction* loop_loss,
                             ceres::LossFunction* wall_loss);
  // Room-layer factors change with every room update: they are made per solve, kept in `costs`.
  void addRoomFactors(ceres::Problem* problem, const Scope& scope, SolveCosts* costs);

  struct KeyframeState {
    std::array<double, 3> t;
    std::array<double, 4> q;  // x y z w
  };
  struct RelativePoseEdge {
    uint32_t from, to;
    std::shared_ptr<ceres::CostFunction> cost;  // RelativePoseCost
    bool robust;
  };
  struct WallObservation {
    uint32_t keyframe, wall;
    std::shared_ptr<ceres::CostFunction> cost;  // WallObservationCost
  };
  struct Room {
    std::array<double, 2> center;
    std::vector<std::pair<uint32_t, uint32_t>> wall_pairs;
    std::optional<Eigen::Vector2d> corridor_anchor;
  };

  BackendConfig config_;
  std::map<uint32_t, KeyframeState> keyframes_;
  std::map<uint32_t, std::array<double, 2>> walls_;
  std::map<uint32_t, Room> rooms_;
  std::vector<RelativePoseEdge> pose_edges_;
  std::vector<WallObservation> wall_observations_;
  // The oldest keyframe that saw each wall: a window solve holds the walls seen before it.
  std::map<uint32_t, uint32_t> first_observer_;
  std::vector<std::pair<uint32_t, uint32_t>> wall_to_wall_;
  std::optional<uint32_t> anchor_keyframe_;
  Eigen::Quaterniond anchor_orientation_ = Eigen::Quaterniond::Identity();  // as first added
};

}  // namespace tacs
