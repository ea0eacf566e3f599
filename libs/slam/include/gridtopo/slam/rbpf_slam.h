#pragma once
// Rao-Blackwellized particle filter grid SLAM with the informed proposal and adaptive resampling
// (Grisetti, Stachniss, Burgard, "Improved techniques for grid mapping with Rao-Blackwellized particle filters",
// IEEE T-RO 23(1), 2007). Feed scans in log order with processScan(); read the trajectory of every scan and the
// best particle's map at any time.
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/motion_model.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
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
  /// Distinct histories the particle set still holds kLineageLag processed scans back: how many of the particles'
  /// ancestors at that step differ (1 = every particle descends from one pose there; the issue-23 diversity curve).
  int lineages = 0;
  /// Processed scans back to the particles' most recent common ancestor (0: they all sit on one pose; the depth of
  /// the tree's root when they never met): how far back the particle set still holds more than one history, so
  /// whether any alternative to the best particle's map reaches a revisit (issue 23, lever 1).
  std::size_t coalescence = 0;
};

/// The lag (processed scans, about 10 m at the default 0.25 m update) at which StepStats::lineages counts ancestors.
inline constexpr std::size_t kLineageLag = 40;

class RbpfSlam {
 public:
  /// Threads of its pool, the caller included.
  int threads() const { return pool_->threads(); }
  explicit RbpfSlam(const SlamOptions& options);

  /// Before the first scan: the pose of the first scan in the map frame (default: its odometry pose, or the
  /// identity without odometry).
  void setInitialPose(const Pose2& pose);
  /// Before the first scan: inserts a scan taken at a known pose into the map every particle starts from
  /// (to continue mapping on top of a previous map).
  void insertKnownScan(const Pose2& robot_pose, const LaserScan& scan);

  /// Feeds the next scan (log order). Returns true if it was processed by the filter (update policy): then, the
  /// paper's steps for every particle: predict with the odometry, scan-match, sample around the mode and fit the
  /// proposal, draw the pose and weight it, update the map; resample when N_eff < resample_threshold·N.
  bool processScan(const ScanRecord& record);

  /// A pose for every scan fed so far: processed scans from the best particle's path, the others from the
  /// neighbouring processed poses plus odometry (blended between the previous and the next processed scan).
  std::vector<TimedPose> trajectory() const;
  /// The same interpolation through given poses of the processed scans (`processed[k]` for the k-th processed
  /// scan, e.g. a pose graph's optimised poses) instead of the best particle's path.
  std::vector<TimedPose> trajectoryThrough(const std::vector<Pose2>& processed) const;
  /// The scan index of the k-th processed scan.
  std::size_t processedScanIndex(std::size_t k) const { return stats_[k].scan_index; }
  /// Continues from a corrected estimate (loop closure fed back): every particle's pose (and its newest
  /// trajectory node) moved by `correction` (applied on the left: x ↦ correction ⊕ x) and its map replaced by
  /// `map` (shared). Between processed scans only.
  void applyCorrection(const Pose2& correction, const GridMap& map);
  std::size_t bestParticleIndex() const;
  const Particle& bestParticle() const { return particles_[bestParticleIndex()]; }
  const std::vector<Particle>& particles() const { return particles_; }
  const std::vector<StepStats>& stats() const { return stats_; }
  const SlamOptions& options() const { return o_; }
  std::size_t scansSeen() const { return scans_.size(); }
  std::size_t stepsProcessed() const { return stats_.size(); }
  /// The last processed scan as the filter prepared it (for the loop closure beside it, which needs the same beams).
  const PreparedScan& lastPreparedScan() const { return last_scan_; }
  /// Distinct tiles over all particles, and in `bytes` if given the bytes of the maps: every particle's block
  /// pointers, the distinct blocks, tiles and hit-mean arrays (each counted once however many share it).
  std::size_t uniqueTiles(std::size_t* bytes = nullptr) const;

 private:
  struct ScanInfo {
    double timestamp;
    bool has_odometry;
    Pose2 odometry;
  };
  /// The odometry increment from the last processed scan to this one, when both carry odometry.
  struct Odometry {
    bool available = false;
    Pose2 u;  ///< in the frame of the last processed scan's odometry pose
  };
  /// Which particles share one proposal plan: duplicates of one particle (same trajectory node and odometry
  /// scale) unless every particle starts its mode search from its own motion sample.
  struct ProposalGroups {
    bool own_start = false;            ///< one group per particle (proposal_start_spread)
    std::vector<std::size_t> leaders;  ///< the particle each group's plan is computed for
    std::vector<std::size_t> group_of;  ///< particle -> group
  };

  bool shouldProcess(const ScanRecord& r) const;
  /// The first processed scan: every particle at the initial pose, with the prior map plus the scan.
  void startParticles(const ScanRecord& record, const PreparedScan& scan, std::size_t index);
  Odometry odometrySinceLastStep(const ScanRecord& record) const;
  /// Predict: each particle's motion increment u (the odometry with the particle's odometry scale, after the
  /// scale's random walk; without odometry a constant-velocity prediction from its last two poses).
  std::vector<Pose2> predictWithOdometry(const ScanRecord& record, const Odometry& odo);
  ProposalGroups groupParticles(bool has_odometry) const;
  /// Scan-match, sample around the mode and fit the proposal (planProposal), once per group, in parallel.
  std::vector<ProposalPlan> matchAndFitProposals(const ProposalGroups& groups, const std::vector<Pose2>& u,
                                                 bool has_odometry, const PreparedScan& scan);
  /// Draw every particle's new pose from its group's proposal and weight it (drawFromProposal); the match
  /// failures and likelihood evaluations go into `st`. `estimates` gets the pose each particle reports in the
  /// trajectory: the informed proposal's mean (proposal_report_mean), else the drawn pose; `matched` whether its
  /// group's scan match succeeded (0: drawn from the motion model).
  std::vector<Pose2> sampleFromProposals(const ProposalGroups& groups, const std::vector<ProposalPlan>& plans,
                                         const std::vector<Pose2>& u, bool has_odometry, const PreparedScan& scan,
                                         StepStats& st, std::vector<Pose2>& estimates, std::vector<char>& matched);
  /// Update the maps: every particle moves to its new pose, inserts the scan there and extends its trajectory
  /// (with the reported estimate of that pose and whether it came from the match).
  void updateMaps(const std::vector<Pose2>& poses, const std::vector<Pose2>& estimates,
                  const std::vector<char>& matched, const PreparedScan& scan,
                  std::size_t index);
  /// The normalised weights (for N_eff and resampling); the log weights are rebased to a maximum of 0.
  std::vector<double> normaliseWeights();
  /// Processed scans back to the particles' most recent common ancestor (StepStats::coalescence).
  std::size_t coalescenceDepth() const;
  /// Resample (low variance) with the normalised weights `w`; survivors restart at weight 1. The new count:
  /// `count` when given, else KLD-sampling's (kld_sampling.h) or the fixed `particles`.
  void resample(const std::vector<double>& w, std::size_t count = 0);
  /// Completes the step's statistics (tile counts every 20 steps, wall time since `t0`) and keeps them.
  void recordStep(StepStats& st, std::chrono::steady_clock::time_point t0);

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
  PreparedScan last_scan_;          // of last_processed_
  double acc_linear_ = 0.0, acc_angular_ = 0.0;
  std::size_t last_unique_tiles_ = 0, last_map_bytes_ = 0;
};

}  // namespace gridtopo::slam
