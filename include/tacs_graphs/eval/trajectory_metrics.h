// Trajectory accuracy: time association, SE(3) alignment, ATE and drift (docs/DESIGN.md
// "Evaluation").
#pragma once

#include <utility>
#include <vector>

#include "tacs_graphs/common/types.h"

namespace tacs {

/// Pairs (estimate index, ground-truth index) whose stamps are nearest and within `max_dt` seconds.
/// Both trajectories must be sorted by stamp.
std::vector<std::pair<size_t, size_t>> associateByTime(const Trajectory& estimate,
                                                       const Trajectory& ground_truth,
                                                       double max_dt);

/// The rigid transform T minimising sum |dst_i - T src_i|^2 (Umeyama without scale). Needs 3+
/// non-collinear points for a unique rotation; with fewer it returns what SVD gives.
Pose3 alignRigid(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst);

struct AteResult {
  double rmse = 0.0;  // metres
  double mean = 0.0;
  double max = 0.0;
  size_t pairs = 0;
  Pose3 T_gt_estimate = Pose3::Identity();  // the alignment applied to the estimate
};

/// Absolute trajectory error of the positions after SE(3) alignment (as `evo_ape -a`).
/// Throws std::invalid_argument when fewer than 3 poses associate.
AteResult computeAte(const Trajectory& estimate, const Trajectory& ground_truth,
                     double max_dt = 0.05);

struct DriftResult {
  double mean_error_m = 0.0;  // mean translation error over segments of `segment_length` metres
  double percent = 0.0;       // the same as a share of the segment length
  size_t segments = 0;
};

/// Relative drift: for every associated pose, the segment to the first pose `segment_length`
/// metres further along the ground-truth path; the error is the norm of the difference between
/// the estimated and the true relative translation (KITTI-style, without alignment).
DriftResult computeDrift(const Trajectory& estimate, const Trajectory& ground_truth,
                         double segment_length = 10.0, double max_dt = 0.05);

/// Length of the path through the trajectory's positions (metres).
double pathLength(const Trajectory& trajectory);

}  // namespace tacs
