// Every factor: zero residual at a consistent configuration, and the automatic-differentiation
// Jacobian equal to central numeric differentiation of the same functor. The analytic costs
// (analytic_costs.h) against the functors they replace: the same residuals, and the same
// Jacobians on the quaternion manifold's tangent space (the only part of an ambient quaternion
// Jacobian that Ceres uses) at random poses, walls and information.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "tacs_graphs/backend/analytic_costs.h"
#include "tacs_graphs/backend/factors.h"
#include "tacs_graphs/common/types.h"

namespace tacs {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// Evaluates `cost` and returns residuals and row-major Jacobians per block.
struct Evaluation {
  std::vector<double> residuals;
  std::vector<std::vector<double>> jacobians;
};

Evaluation evaluate(const ceres::CostFunction& cost, const std::vector<double*>& params) {
  Evaluation e;
  e.residuals.resize(cost.num_residuals());
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<double*> jac_ptrs;
  for (size_t i = 0; i < sizes.size(); ++i) {
    e.jacobians.emplace_back(cost.num_residuals() * sizes[i]);
    jac_ptrs.push_back(e.jacobians.back().data());
  }
  EXPECT_TRUE(cost.Evaluate(params.data(), e.residuals.data(), jac_ptrs.data()));
  return e;
}

template <class Functor, int... Sizes>
void expectJacobiansMatchNumeric(Functor* functor, const std::vector<double*>& params) {
  ceres::AutoDiffCostFunction<Functor, Sizes...> autodiff(new Functor(*functor));
  ceres::NumericDiffCostFunction<Functor, ceres::CENTRAL, Sizes...> numeric(new Functor(*functor),
                                                                            ceres::TAKE_OWNERSHIP);
  const Evaluation a = evaluate(autodiff, params);
  const Evaluation n = evaluate(numeric, params);
  for (size_t i = 0; i < a.residuals.size(); ++i)
    EXPECT_NEAR(a.residuals[i], n.residuals[i], 1e-12);
  for (size_t b = 0; b < a.jacobians.size(); ++b) {
    for (size_t k = 0; k < a.jacobians[b].size(); ++k) {
      EXPECT_NEAR(a.jacobians[b][k], n.jacobians[b][k], 1e-6) << "block " << b << " entry " << k;
    }
  }
  delete functor;
}

std::array<double, 4> quat(const Pose3& p) {
  const Eigen::Quaterniond q(p.rotation());
  return {q.x(), q.y(), q.z(), q.w()};
}
std::array<double, 3> trans(const Pose3& p) {
  return {p.translation().x(), p.translation().y(), p.translation().z()};
}

TEST(RelativePoseFactor, ZeroAtTruthAndJacobianMatchesNumeric) {
  const Pose3 a = poseFromXyzRpy(1, 2, 0.1, 0.02, -0.01, 0.4);
  const Pose3 b = poseFromXyzRpy(2.5, 1.0, 0.2, -0.03, 0.02, 1.3);
  Matrix6d sqrt_info = Matrix6d::Identity() * 3.0;
  RelativePoseFactor f(a.inverse() * b, sqrt_info);
  auto ta = trans(a), tb = trans(b);
  auto qa = quat(a), qb = quat(b);
  double r[6];
  f(ta.data(), qa.data(), tb.data(), qb.data(), r);
  for (double v : r) EXPECT_NEAR(v, 0.0, 1e-12);
  // Away from the truth the residual grows with the error.
  tb[0] += 0.1;
  f(ta.data(), qa.data(), tb.data(), qb.data(), r);
  const double norm = Eigen::Map<Eigen::Matrix<double, 6, 1>>(r).norm();
  EXPECT_NEAR(norm, 0.3, 1e-9);
  expectJacobiansMatchNumeric<RelativePoseFactor, 6, 3, 4, 3, 4>(
      new RelativePoseFactor(f), {ta.data(), qa.data(), tb.data(), qb.data()});
}

TEST(WallObservationFactor, ZeroAtTruthAndJacobianMatchesNumeric) {
  const Pose3 kf = poseFromXyzRpy(1.0, -2.0, 0.3, 0.01, 0.02, 0.7);
  double wall[2] = {0.3, -4.0};  // n = (cos .3, sin .3, 0), d = -4
  const Eigen::Vector3d n(std::cos(wall[0]), std::sin(wall[0]), 0.0);
  const Eigen::Vector3d n_b = kf.rotation().transpose() * n;
  const double d_b = wall[1] + n.dot(kf.translation());
  WallObservationFactor f(n_b, d_b, 0.05, 0.05);
  auto t = trans(kf);
  auto q = quat(kf);
  double r[4];
  f(t.data(), q.data(), wall, r);
  for (double v : r) EXPECT_NEAR(v, 0.0, 1e-12);
  // Moving the wall by 5 cm shows as one sigma of distance error.
  wall[1] += 0.05;
  f(t.data(), q.data(), wall, r);
  EXPECT_NEAR(r[3], 1.0, 1e-9);
  expectJacobiansMatchNumeric<WallObservationFactor, 4, 3, 4, 2>(new WallObservationFactor(f),
                                                                 {t.data(), q.data(), wall});
}

TEST(RoomPairFactor, ZeroMidwayAndJacobianMatchesNumeric) {
  // Walls x = 0 (normal +x, facing in) and x = 4 (normal -x): centre x = 2.
  double wall_a[2] = {0.0, 0.0};
  double wall_b[2] = {M_PI, 4.0};
  double c[2] = {2.0, 7.0};
  RoomPairFactor f(0.1);
  double r;
  f(c, wall_a, wall_b, &r);
  EXPECT_NEAR(r, 0.0, 1e-12);
  c[0] = 2.5;
  f(c, wall_a, wall_b, &r);
  EXPECT_NEAR(r, 10.0, 1e-9);  // 0.5 m off-centre: distances differ by 1 m = 10 sigma
  expectJacobiansMatchNumeric<RoomPairFactor, 1, 2, 2, 2>(new RoomPairFactor(f),
                                                          {c, wall_a, wall_b});
}

TEST(CorridorAnchorFactor, MeasuresOnlyAlongTheWall) {
  double wall[2] = {0.0, -1.0};  // wall x = 1, corridor along y
  double c[2] = {3.0, 5.0};
  CorridorAnchorFactor f(Eigen::Vector2d(0.0, 5.0), 0.5);
  double r;
  f(c, wall, &r);
  EXPECT_NEAR(r, 0.0, 1e-12);  // offset across the corridor is free
  c[1] = 6.0;
  f(c, wall, &r);
  EXPECT_NEAR(r, 2.0, 1e-9);
  expectJacobiansMatchNumeric<CorridorAnchorFactor, 1, 2, 2>(new CorridorAnchorFactor(f),
                                                             {c, wall});
}

TEST(WallToWallFactor, WrapsAnglesAndJacobianMatchesNumeric) {
  double a[2] = {M_PI - 0.01, 2.0};
  double b[2] = {-M_PI + 0.01, 2.1};
  WallToWallFactor f(0.02, 0.05);
  double r[2];
  f(a, b, r);
  EXPECT_NEAR(r[0], 1.0, 1e-9);  // 0.02 rad across the +-pi seam, not 2 pi
  EXPECT_NEAR(r[1], 2.0, 1e-9);
  expectJacobiansMatchNumeric<WallToWallFactor, 2, 2, 2>(new WallToWallFactor(f), {a, b});
}

struct TangentEvaluation {
  std::vector<double> residuals;
  std::vector<Eigen::MatrixXd> jacobians;  // per block; quaternion blocks on the tangent space
};

TangentEvaluation evaluateOnTangent(const ceres::CostFunction& cost,
                                    const std::vector<double*>& params,
                                    const std::vector<bool>& is_quaternion) {
  const auto& sizes = cost.parameter_block_sizes();
  const int rows = cost.num_residuals();
  std::vector<std::vector<double>> raw(sizes.size());
  std::vector<double*> ptrs;
  for (size_t b = 0; b < sizes.size(); ++b) {
    raw[b].resize(rows * sizes[b]);
    ptrs.push_back(raw[b].data());
  }
  TangentEvaluation e;
  e.residuals.resize(rows);
  EXPECT_TRUE(cost.Evaluate(params.data(), e.residuals.data(), ptrs.data()));
  const ceres::EigenQuaternionManifold manifold;
  for (size_t b = 0; b < sizes.size(); ++b) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::MatrixXd ambient = Eigen::Map<const RowMajor>(raw[b].data(), rows, sizes[b]);
    if (!is_quaternion[b]) {
      e.jacobians.push_back(ambient);
      continue;
    }
    Eigen::Matrix<double, 4, 3, Eigen::RowMajor> plus;
    manifold.PlusJacobian(params[b], plus.data());
    e.jacobians.push_back(ambient * plus);
  }
  return e;
}

void expectSame(const TangentEvaluation& analytic, const TangentEvaluation& autodiff) {
  ASSERT_EQ(analytic.residuals.size(), autodiff.residuals.size());
  for (size_t i = 0; i < analytic.residuals.size(); ++i)
    EXPECT_NEAR(analytic.residuals[i], autodiff.residuals[i], 1e-12) << "residual " << i;
  for (size_t b = 0; b < analytic.jacobians.size(); ++b) {
    const double scale = std::max(1.0, autodiff.jacobians[b].cwiseAbs().maxCoeff());
    EXPECT_LT((analytic.jacobians[b] - autodiff.jacobians[b]).cwiseAbs().maxCoeff(), 1e-9 * scale)
        << "block " << b << "\nanalytic\n"
        << analytic.jacobians[b] << "\nautodiff\n"
        << autodiff.jacobians[b];
  }
}

Pose3 randomPose(std::mt19937* rng, double extent) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Quaterniond q =
      Eigen::Quaterniond(Eigen::Vector4d(u(*rng), u(*rng), u(*rng), u(*rng))).normalized();
  Pose3 T = Pose3::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = extent * Eigen::Vector3d(u(*rng), u(*rng), u(*rng));
  return T;
}

TEST(RelativePoseCost, MatchesTheAutodiffFactorAwayFromItsMeasurement) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 a = randomPose(&rng, 20.0), b = randomPose(&rng, 20.0);
    const Pose3 measured = randomPose(&rng, 3.0);
    Eigen::Matrix<double, 6, 6> sqrt_info = Eigen::Matrix<double, 6, 6>::Random();
    sqrt_info.diagonal().array() += 5.0;  // full, not diagonal, as an odometry edge's is
    auto ta = trans(a), tb = trans(b);
    auto qa = quat(a), qb = quat(b);
    const std::vector<double*> params = {ta.data(), qa.data(), tb.data(), qb.data()};
    const std::vector<bool> quaternions = {false, true, false, true};
    const RelativePoseCost analytic(measured, sqrt_info);
    const ceres::AutoDiffCostFunction<RelativePoseFactor, 6, 3, 4, 3, 4> autodiff(
        new RelativePoseFactor(measured, sqrt_info));
    expectSame(evaluateOnTangent(analytic, params, quaternions),
               evaluateOnTangent(autodiff, params, quaternions));
  }
}

TEST(WallObservationCost, MatchesTheAutodiffFactorAwayFromItsMeasurement) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose3 kf = randomPose(&rng, 20.0);
    double wall[2] = {M_PI * u(rng), 10.0 * u(rng)};
    const Eigen::Vector3d n_obs = Eigen::Vector3d(u(rng), u(rng), 0.2 * u(rng)).normalized();
    const double d_obs = 5.0 * u(rng);
    auto t = trans(kf);
    auto q = quat(kf);
    const std::vector<double*> params = {t.data(), q.data(), wall};
    const std::vector<bool> quaternions = {false, true, false};
    const WallObservationCost analytic(n_obs, d_obs, 0.05, 0.08);
    const ceres::AutoDiffCostFunction<WallObservationFactor, 4, 3, 4, 2> autodiff(
        new WallObservationFactor(n_obs, d_obs, 0.05, 0.08));
    expectSame(evaluateOnTangent(analytic, params, quaternions),
               evaluateOnTangent(autodiff, params, quaternions));
  }
}

TEST(WallObservationCost, LeavesOutJacobiansCeresDoesNotAskFor) {
  // A held keyframe's blocks are constant: Ceres passes null for their Jacobians.
  const Pose3 kf = Pose3::Identity();
  double wall[2] = {0.0, -2.0};
  auto t = trans(kf);
  auto q = quat(kf);
  const double* params[] = {t.data(), q.data(), wall};
  const WallObservationCost cost(Eigen::Vector3d::UnitX(), -2.5, 0.05, 0.05);
  double residuals[4];
  double wall_jacobian[8];
  double* jacobians[] = {nullptr, nullptr, wall_jacobian};
  ASSERT_TRUE(cost.Evaluate(params, residuals, jacobians));
  EXPECT_NEAR(residuals[3], 10.0, 1e-12);      // 0.5 m at sigma 0.05
  EXPECT_NEAR(wall_jacobian[7], 20.0, 1e-12);  // d residual_d / d d = 1 / sigma_d
}

}  // namespace
}  // namespace tacs
