#pragma once
// Rao-Blackwellized particle filter grid SLAM with the informed proposal and adaptive resampling
// (Grisetti, Stachniss, Burgard, "Improved techniques for grid mapping with Rao-Blackwellized particle filters",
// IEEE T-RO 23(1), 2007). Feed scans in log order with processScan(); read the trajectory of every scan and the
// best particle's map at any time.
#include <cstddef>
#include <memory>
#include <vector>

#include "gridtopo/io/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/motion_model.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/slam/thread_pool.h"
#include "gridtopo/slam/trajectory_tree.h"

namespace gridtopo::slam {

struct Particle {
  Pose2 pose;
  double log_weight = 0.0;        ///< since the last resampling (relative; normalised every step)
  double log_weight_total = 0.0;  ///< accumulated over the whole run, inherited at resampling (best-particle choice)
  TrajectoryNodePtr node;
  GridMap map;
  /// Factor on the translation of the odometry increments (motion_scale_sigma; 1 when off). Inherited at
  /// resampling like the map.
  double odometry_scale = 1.0;
};

/// What happened at one processed scan (one line of the stats file).
struct StepStats {
  std::size_t step = 0;        ///< processed-scan counter
  std::size_t scan_index = 0;  ///< input index of the scan
  double timestamp = 0.0;
  double time_s = 0.0;         ///< wall time of the step
  double neff = 0.0;           ///< before resampling
  bool resampled = false;
  int particles = 0;
  int failed_matches = 0;      ///< particles that fell back to the odometry proposal
  double evaluations = 0.0;    ///< mean likelihood evaluations per particle
  std::size_t unique_tiles = 0;  ///< distinct map tiles over all particles (counted every 20 steps)
  std::size_t map_bytes = 0;     ///< memory of those tiles
};

/// The deterministic part of one particle's step (predict, match, sample around the mode, fit the proposal):
/// it depends only on the particle's map and previous pose, so particles duplicated by resampling share it.
struct ProposalPlan {
  bool matched = false;            ///< false: fall back to the odometry proposal
  ProposalType type = ProposalType::Informed;
  GaussianProposal gaussian;       ///< informed: N(μ, Σ) and ln η; mode-only: the mode in `mean`
  double log_weight_increment = 0.0;  ///< ln(η·Δx·Δy·Δθ) ≈ ln ∫ p(z|m,x)^(1/gain) p(x|x_{t-1},u) dx
  int evaluations = 0;             ///< likelihood evaluations (scan matching + proposal)
};

/// Plans the proposal for a particle at `prev` with odometry increment `u` (in the frame of `prev`). The mode
/// search starts at `start` when given (proposal_start_spread > 0), else at the prediction prev ⊕ u.
ProposalPlan planProposal(const GridMap& map, const Pose2& prev, const Pose2& u, bool has_odometry,
                          const PreparedScan& scan, const SlamOptions& o, const OdometryMotionModel& motion,
                          const Pose2* start = nullptr);

/// Draws the particle's new pose from the plan with the particle's own random stream; returns the weight
/// increment (ln η for the informed proposal, ln p(z|m,x)/gain for mode-only and odometry).
double drawFromProposal(const ProposalPlan& plan, const GridMap& map, const Pose2& prev, const Pose2& u,
                        bool has_odometry, const PreparedScan& scan, const SlamOptions& o,
                        const OdometryMotionModel& motion, Rng& rng, Pose2& out_pose);

class RbpfSlam {
 public:
  explicit RbpfSlam(const SlamOptions& options);

  /// Before the first scan: the pose of the first scan in the map frame (default: its odometry pose, or the
  /// identity without odometry).
  void setInitialPose(const Pose2& pose);
  /// Before the first scan: inserts a scan taken at a known pose into the map every particle starts from
  /// (to continue mapping on top of a previous map).
  void insertKnownScan(const Pose2& robot_pose, const io::LaserScan& scan);

  /// Feeds the next scan (log order). Returns true if it was processed by the filter (update policy).
  bool processScan(const io::ScanRecord& record);

  /// A pose for every scan fed so far: processed scans from the best particle's path, the others from the
  /// neighbouring processed poses plus odometry (blended between the previous and the next processed scan).
  std::vector<io::TimedPose> trajectory() const;
  std::size_t bestParticleIndex() const;
  const Particle& bestParticle() const { return particles_[bestParticleIndex()]; }
  const std::vector<Particle>& particles() const { return particles_; }
  const std::vector<StepStats>& stats() const { return stats_; }
  const SlamOptions& options() const { return o_; }
  std::size_t scansSeen() const { return scans_.size(); }
  std::size_t stepsProcessed() const { return stats_.size(); }
  /// Distinct tiles over all particles, and in `bytes` if given the bytes of the maps: every particle's block
  /// pointers, the distinct blocks, tiles and hit-mean arrays (each counted once however many share it).
  std::size_t uniqueTiles(std::size_t* bytes = nullptr) const;

 private:
  struct ScanInfo {
    double timestamp;
    bool has_odometry;
    Pose2 odometry;
  };
  bool shouldProcess(const io::ScanRecord& r) const;
  void resample(const std::vector<double>& w);

  SlamOptions o_;
  OdometryMotionModel motion_;
  std::unique_ptr<ThreadPool> pool_;
  std::vector<Particle> particles_;
  std::vector<ScanInfo> scans_;
  std::vector<StepStats> stats_;
  bool initialized_ = false;
  bool has_initial_pose_ = false;
  Pose2 initial_pose_;
  GridMap prior_map_;
  std::size_t last_processed_ = 0;  // scan index
  double acc_linear_ = 0.0, acc_angular_ = 0.0;
  std::size_t last_unique_tiles_ = 0, last_map_bytes_ = 0;
};

}  // namespace gridtopo::slam
