#include "gridtopo/slam/pose_graph.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <memory>

namespace gridtopo::slam {

namespace {

template <typename T>
T normalizeAngle(const T& a) {
  const T two_pi(2.0 * 3.14159265358979323846);
  return a - two_pi * ceres::floor((a + T(3.14159265358979323846)) / two_pi);
}

/// Residual of one relative-pose edge: L · (p_a⁻¹ ⊕ p_b − z), angle wrapped.
struct RelativePoseError {
  RelativePoseError(const Pose2& z, const Eigen::Matrix3d& L) : z_(z), L_(L) {}
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    const T c = ceres::cos(a[2]), s = ceres::sin(a[2]);
    const T dx = b[0] - a[0], dy = b[1] - a[1];
    T e[3];
    e[0] = c * dx + s * dy - T(z_.x);
    e[1] = -s * dx + c * dy - T(z_.y);
    e[2] = normalizeAngle(b[2] - a[2] - T(z_.theta));
    for (int i = 0; i < 3; ++i) r[i] = T(L_(i, 0)) * e[0] + T(L_(i, 1)) * e[1] + T(L_(i, 2)) * e[2];
    return true;
  }
  Pose2 z_;
  Eigen::Matrix3d L_;
};

}  // namespace

std::size_t PoseGraph::addNode(const Pose2& initial) {
  nodes_.push_back(initial);
  return nodes_.size() - 1;
}

std::size_t PoseGraph::addEdge(const PoseGraphEdge& e) {
  edges_.push_back(e);
  return edges_.size() - 1;
}

Eigen::Vector3d PoseGraph::residual(const PoseGraphEdge& e) const {
  const Pose2 d = relative(nodes_[e.a], nodes_[e.b]);
  const Eigen::Vector3d err(d.x - e.z.x, d.y - e.z.y, wrapAngle(d.theta - e.z.theta));
  return e.sqrt_information * err;
}

double PoseGraph::optimize(const PoseGraphSolveOptions& o) {
  if (nodes_.size() < 2) return 0.0;
  std::vector<std::array<double, 3>> x(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) x[i] = {nodes_[i].x, nodes_[i].y, nodes_[i].theta};
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (const PoseGraphEdge& e : edges_) {
    if (!e.active) continue;
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3>(new RelativePoseError(e.z, e.sqrt_information));
    ceres::LossFunction* loss = e.robust ? new ceres::HuberLoss(o.huber_scale) : nullptr;
    problem.AddResidualBlock(cost, loss, x[e.a].data(), x[e.b].data());
  }
  problem.SetParameterBlockConstant(x[0].data());
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  so.max_num_iterations = o.max_iterations;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  for (std::size_t i = 0; i < nodes_.size(); ++i) nodes_[i] = {x[i][0], x[i][1], wrapAngle(x[i][2])};
  return summary.final_cost;
}

Eigen::Matrix3d sqrtInformationOfSigmas(double sx, double sy, double st) {
  Eigen::Matrix3d L = Eigen::Matrix3d::Zero();
  L(0, 0) = 1.0 / sx;
  L(1, 1) = 1.0 / sy;
  L(2, 2) = 1.0 / st;
  return L;
}

Eigen::Matrix3d sqrtInformationOfCovariance(const Eigen::Matrix3d& cov) {
  const Eigen::Matrix3d info = cov.inverse();
  const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (info + info.transpose()));
  return llt.matrixU();  // info = Uᵀ U, so ‖U e‖² = eᵀ info e
}

}  // namespace gridtopo::slam
