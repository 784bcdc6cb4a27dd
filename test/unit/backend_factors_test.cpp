// Every factor: zero residual at a consistent configuration, and the automatic-differentiation
// Jacobian equal to central numeric differentiation of the same functor.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>

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

}  // namespace
}  // namespace tacs
