#include "tacs_graphs/backend/analytic_costs.h"

#include <ceres/manifold.h>

#include "tacs_graphs/common/types.h"

namespace tacs {
namespace {

using RowMajor34 = Eigen::Matrix<double, 3, 4, Eigen::RowMajor>;

// 2 P^T: the ambient Jacobian of a rotation perturbation (see the header) is J_phi * 2 P^T.
RowMajor34 twicePlusJacobianTransposed(const double* q) {
  static const ceres::EigenQuaternionManifold kManifold;
  Eigen::Matrix<double, 4, 3, Eigen::RowMajor> P;
  kManifold.PlusJacobian(q, P.data());
  return 2.0 * P.transpose();
}

}  // namespace

RelativePoseCost::RelativePoseCost(const Eigen::Isometry3d& T_ab,
                                   const Eigen::Matrix<double, 6, 6>& sqrt_info)
    : t_ab_(T_ab.translation()), q_ab_(T_ab.rotation()), sqrt_info_(sqrt_info) {}

bool RelativePoseCost::Evaluate(double const* const* parameters, double* residuals,
                                double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> p_a(parameters[0]), p_b(parameters[2]);
  const Eigen::Map<const Eigen::Quaterniond> q_a(parameters[1]), q_b(parameters[3]);
  const Eigen::Quaterniond q_a_inv = q_a.conjugate();
  const Eigen::Vector3d delta = p_b - p_a;
  // A = q_ab^-1 q_a^-1: the error quaternion is A q_b (RelativePoseFactor).
  const Eigen::Quaterniond A = q_ab_.conjugate() * q_a_inv;
  const Eigen::Quaterniond q_err = q_ab_.conjugate() * (q_a_inv * q_b);
  Eigen::Matrix<double, 6, 1> r;
  r.head<3>() = q_a_inv * delta - t_ab_;
  r.tail<3>() = 2.0 * q_err.vec();
  Eigen::Map<Eigen::Matrix<double, 6, 1>> out(residuals);
  out = sqrt_info_ * r;
  if (!jacobians) return true;

  const Eigen::Matrix3d Ra_T = q_a_inv.toRotationMatrix();
  // Rotating q_b by phi turns q_err into [R_A phi / 2, 1] q_err; rotating q_a by phi, into
  // [-R_A phi / 2, 1] q_err. d vec([u, 1] q) / du = w I - [v]x for q = [v, w].
  const Eigen::Matrix3d dvec =
      (q_err.w() * Eigen::Matrix3d::Identity() - skew(q_err.vec())) * A.toRotationMatrix();
  using RowMajor63 = Eigen::Matrix<double, 6, 3, Eigen::RowMajor>;
  using RowMajor64 = Eigen::Matrix<double, 6, 4, Eigen::RowMajor>;
  if (jacobians[0]) {
    RowMajor63 J;
    J << -Ra_T, Eigen::Matrix3d::Zero();
    Eigen::Map<RowMajor63> out_0(jacobians[0]);
    out_0 = sqrt_info_ * J;
  }
  if (jacobians[1]) {
    RowMajor63 J;
    J << Ra_T * skew(delta), -dvec;
    Eigen::Map<RowMajor64> out_1(jacobians[1]);
    out_1 = sqrt_info_ * J * twicePlusJacobianTransposed(parameters[1]);
  }
  if (jacobians[2]) {
    RowMajor63 J;
    J << Ra_T, Eigen::Matrix3d::Zero();
    Eigen::Map<RowMajor63> out_2(jacobians[2]);
    out_2 = sqrt_info_ * J;
  }
  if (jacobians[3]) {
    RowMajor63 J;
    J << Eigen::Matrix3d::Zero(), dvec;
    Eigen::Map<RowMajor64> out_3(jacobians[3]);
    out_3 = sqrt_info_ * J * twicePlusJacobianTransposed(parameters[3]);
  }
  return true;
}

WallObservationCost::WallObservationCost(const Eigen::Vector3d& n_obs, double d_obs, double sigma_n,
                                         double sigma_d)
    : n_obs_(n_obs), d_obs_(d_obs), inv_sigma_n_(1.0 / sigma_n), inv_sigma_d_(1.0 / sigma_d) {}

bool WallObservationCost::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> p(parameters[0]);
  const Eigen::Map<const Eigen::Quaterniond> q(parameters[1]);
  const double theta = parameters[2][0];
  const Eigen::Vector3d n(std::cos(theta), std::sin(theta), 0.0);
  const Eigen::Vector3d n_b = q.conjugate() * n;  // wallInBase
  const double d_b = parameters[2][1] + n.dot(p);
  for (int i = 0; i < 3; ++i) residuals[i] = (n_b[i] - n_obs_[i]) * inv_sigma_n_;
  residuals[3] = (d_b - d_obs_) * inv_sigma_d_;
  if (!jacobians) return true;

  const Eigen::Matrix3d R_T = q.conjugate().toRotationMatrix();
  const Eigen::Vector3d dn_dtheta(-n.y(), n.x(), 0.0);
  if (jacobians[0]) {
    Eigen::Map<Eigen::Matrix<double, 4, 3, Eigen::RowMajor>> J(jacobians[0]);
    J.topRows<3>().setZero();
    J.row(3) = inv_sigma_d_ * n.transpose();
  }
  if (jacobians[1]) {
    // n_b = R^T n; rotating R by phi gives R^T n + R^T [n]x phi.
    Eigen::Matrix<double, 4, 3, Eigen::RowMajor> J;
    J.topRows<3>() = inv_sigma_n_ * R_T * skew(n);
    J.row(3).setZero();
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> out(jacobians[1]);
    out = J * twicePlusJacobianTransposed(parameters[1]);
  }
  if (jacobians[2]) {
    Eigen::Map<Eigen::Matrix<double, 4, 2, Eigen::RowMajor>> J(jacobians[2]);
    J.block<3, 1>(0, 0) = inv_sigma_n_ * R_T * dn_dtheta;
    J.block<3, 1>(0, 1).setZero();
    J(3, 0) = inv_sigma_d_ * dn_dtheta.dot(p);
    J(3, 1) = inv_sigma_d_;
  }
  return true;
}

}  // namespace tacs
