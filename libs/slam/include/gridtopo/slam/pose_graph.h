#pragma once
// A 2D pose graph optimised by Ceres (Agarwal, Mierle et al., the solver Cartographer uses): nodes are poses
// (x, y, θ); an edge says "node b seen from node a is z" with a 3×3 square-root information; closures carry a
// Huber loss so that one wrong closure pulls with a bounded force instead of tearing the map (Hess et al. 2016,
// sec. VI). The first node is held fixed.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

struct PoseGraphEdge {
  std::size_t a = 0, b = 0;
  Pose2 z;                                         ///< b in the frame of a
  Eigen::Matrix3d sqrt_information = Eigen::Matrix3d::Identity();  ///< L with information LᵀL; residual = L·(ẑ − z)
  bool robust = false;                             ///< Huber loss (closures)
  bool active = true;                              ///< false: left out of the optimisation (a rejected closure)
};

struct PoseGraphSolveOptions {
  double huber_scale = 3.0;  ///< on the whitened residual's norm
  int max_iterations = 30;
};

class PoseGraph {
 public:
  std::size_t addNode(const Pose2& initial);
  /// Adds an edge; returns its index.
  std::size_t addEdge(const PoseGraphEdge& e);
  void replaceEdge(std::size_t i, const PoseGraphEdge& e) { edges_[i] = e; }
  /// Leaves an edge out of later optimisations.
  void deactivateEdge(std::size_t i) { edges_[i].active = false; }
  std::size_t size() const { return nodes_.size(); }
  const Pose2& pose(std::size_t i) const { return nodes_[i]; }
  void setPose(std::size_t i, const Pose2& p) { nodes_[i] = p; }
  const std::vector<PoseGraphEdge>& edges() const { return edges_; }
  /// Optimises every node but the first from the current poses; returns the final cost (½ Σ ρ(‖r‖²)).
  /// Single-threaded: the result is the same whatever the run's thread count.
  double optimize(const PoseGraphSolveOptions& o);

  /// The whitened residual of an edge at the current poses.
  Eigen::Vector3d residual(const PoseGraphEdge& e) const;

 private:
  std::vector<Pose2> nodes_;
  std::vector<PoseGraphEdge> edges_;
};

/// The square-root information of a diagonal deviation (σx, σy, σθ).
Eigen::Matrix3d sqrtInformationOfSigmas(double sx, double sy, double st);
/// The upper-triangular square root of the inverse of a covariance (Cholesky of the information).
Eigen::Matrix3d sqrtInformationOfCovariance(const Eigen::Matrix3d& cov);

}  // namespace gridtopo::slam
