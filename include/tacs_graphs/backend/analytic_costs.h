// The two factors that make up nearly every residual of the graph, with hand-written Jacobians:
// the same residuals as RelativePoseFactor and WallObservationFactor (factors.h), which stay the
// reference the tests compare against. Automatic differentiation of these two was a third of the
// backend's time (results/throughput.md, t_FGO).
//
// Rotations are differentiated by a left perturbation R' = exp([phi]x) R, the one
// ceres::EigenQuaternionManifold applies (x + delta = [delta, 1] * x, phi = 2 delta); the
// Jacobian handed to Ceres is the ambient one, J_phi * 2 * P^T, which the manifold's plus Jacobian
// P (P^T P = I at a unit quaternion) turns back into J_phi * 2.
#pragma once

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tacs {

/// RelativePoseFactor with analytic Jacobians. Parameter blocks: t_a[3], q_a[4], t_b[3], q_b[4].
class RelativePoseCost final : public ceres::SizedCostFunction<6, 3, 4, 3, 4> {
 public:
  RelativePoseCost(const Eigen::Isometry3d& T_ab, const Eigen::Matrix<double, 6, 6>& sqrt_info);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d t_ab_;
  Eigen::Quaterniond q_ab_;
  Eigen::Matrix<double, 6, 6> sqrt_info_;
};

/// WallObservationFactor with analytic Jacobians. Parameter blocks: t[3], q[4], wall[2].
class WallObservationCost final : public ceres::SizedCostFunction<4, 3, 4, 2> {
 public:
  WallObservationCost(const Eigen::Vector3d& n_obs, double d_obs, double sigma_n, double sigma_d);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d n_obs_;
  double d_obs_;
  double inv_sigma_n_, inv_sigma_d_;
};

}  // namespace tacs
