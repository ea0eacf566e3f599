#pragma once
// Loop closure beyond the filter: a pose graph over the best particle's processed poses (the approach of
// graph-based 2D SLAM: Hess, Kohler, Rapp, Andor, "Real-time loop closure in 2D LIDAR SLAM", ICRA 2016; Konolige
// et al.'s Karto). Run incrementally, in time order, beside the filter:
//   1. addFilterMotion: a node per processed scan, joined to the previous node by the filter's own motion;
//   2. searchForClosures: the newest scans (the query) are matched against older submaps (runs of consecutive
//      scans) that the current estimate places inside a search window, which grows with the drift the graph's
//      least-drift path to the submap can have gathered (accepted closures are shortcuts); an exhaustive
//      branch-and-bound search (correlative_matcher.h), a minimum score, and a second search that refuses the
//      match when a distinct pose scores nearly as well (look-alike corridors);
//   3. optimizePoseGraph: Ceres with a Huber loss on the closures (pose_graph.h), every optimize_every scans
//      while closures are pending;
//   4. the correction of the newest pose, which the caller may feed back into the filter (SlamRun).
// And, beyond the drift window (global_search):
//   5. signOlderPlaces: every older stretch of the trajectory gets a place signature (place_signature.h, Scan
//      Context after Kim & Kim, IROS 2018), centred on its middle pose (the same for the way there and back);
//   6. proposeGlobalClosures: the newest stretch's signature ranks them all, wherever the estimate puts them; the
//      best are matched exactly (branch and bound around the signature's place and heading);
//   7. verifyGlobalClosures: a match enters the graph only once global_agree independent matches agree with each
//      other and with the trajectory between them (pairwise consistency, after Mangelson, Dominic, Eustice,
//      Vasudevan, "Pairwise consistent measurement set maximization for robust multi-robot map merging", ICRA 2018),
//      (no bound on the drift itself: a building's odometry can drift by a third of the travel).
// The final trajectory and map are rebuilt from the optimised poses.
#include <cstddef>
#include <functional>
#include <optional>
#include <list>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "gridtopo/slam/correlative_matcher.h"
#include "gridtopo/slam/loop_closure_options.h"
#include "gridtopo/slam/motion_model.h"
#include "gridtopo/slam/observed_area.h"
#include "gridtopo/slam/place_signature.h"
#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/pose_graph.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::slam {

/// One accepted closure (a line of stats.txt's closure table).
struct LoopClosureRecord {
  std::size_t node = 0;        ///< the newest node when found (processed-scan counter)
  std::size_t scan_index = 0;  ///< its input scan index
  double timestamp = 0.0;
  std::size_t submap_node = 0;  ///< the submap's first node (the edge's other end)
  double score = 0.0;           ///< mean correlation over the query's points
  double window_xy = 0.0;       ///< m, the search's half-width
  double offset_xy = 0.0;       ///< m, how far the match lies from the estimate it started from
  double offset_theta = 0.0;    ///< rad
  /// How far the optimisation that took it in moved the newest pose (m, rad); set at that optimisation.
  double correction_xy = 0.0, correction_theta = 0.0;
  double residual = 0.0;  ///< its whitened residual after that optimisation (standard deviations)
  bool rejected = false;  ///< left out after that optimisation (residual above outlier_sigmas)
  bool global = false;    ///< proposed by the place signatures beyond the drift window and verified by agreement
  std::size_t edge = 0;   ///< its edge in the pose graph
};

/// What the loop closure did over a run (the summary line of stats.txt).
struct LoopClosureCounts {
  std::size_t nodes = 0, searches = 0, accepted = 0, rejected = 0, ambiguous = 0, on_border = 0, suspect_steps = 0,
              optimizations = 0;
  /// The global search: searches, exact matches refuted by what the place saw (observed_area.h), matches proposed
  /// (of them, followed: found where a waiting match predicted the query), matches refused because the short
  /// trajectory between the place and the query contradicts them, matches accepted (after agreement), matches
  /// dropped for want of agreement.
  std::size_t global_searches = 0, global_refuted = 0, global_proposed = 0, global_followed = 0,
              global_contradicted = 0, global_accepted = 0, global_dropped = 0;
  /// Candidates not matched because every pose of their search window lies beyond the drift bound: the match
  /// would have been refused (or never found); deciding it first saves the place's grid and the search.
  std::size_t global_beyond_bound = 0;
  /// The largest move of the newest pose by an optimisation with new accepted closures (m, rad), from where the
  /// filter's motions since the previous optimisation put it.
  double largest_correction_xy = 0.0, largest_correction_theta = 0.0;
  /// Processor seconds (of the thread that ran them) spent in each part: the windowed search (with its backfill),
  /// the global search's signatures, its queries (ranking and exact matches) and the agreement of its matches, and
  /// the optimisations. Not deterministic: written apart from the counts (loopClosureCpuText).
  double cpu_windowed = 0.0, cpu_global_sign = 0.0, cpu_global_query = 0.0, cpu_global_verify = 0.0,
         cpu_optimize = 0.0;
};

/// What one step of the loop closure did.
struct LoopClosureStep {
  int accepted = 0;        ///< closures added
  bool optimized = false;
  Pose2 newest_before, newest_after;  ///< the newest node before and after the optimisation
  bool feedback = false;   ///< the correction is large enough to feed back into the filter
};

class LoopCloser {
 public:
  /// `motion` is the filter's motion model: the yardstick of the filter's disagreement with the odometry.
  LoopCloser(const LoopClosureOptions& options, const MotionModelOptions& motion);

  /// Adds the node of processed scan `scan_index`: the first at `filter_pose`, the others joined to the previous
  /// node by `motion` (the filter's estimate of the motion since the previous processed scan, in its frame), then
  /// searches for closures and optimises when due. `odometry` is the odometry's motion over the same step (null
  /// without odometry): where the filter and the odometry disagree, one of them is wrong, so the motion edge is
  /// that much weaker and the search window that much wider.
  /// Where the motion edges come from at each optimisation and at the end: the filter's current best path (one
  /// pose per node so far). Without it the edges keep the motion given to addScan (the best particle's then).
  /// Each step also says whether its pose came from a scan match (see LoopClosureOptions::unmatched_steps_as_odometry).
  struct FilterStep {
    Pose2 estimate;
    bool matched = true;
  };
  void setFilterPath(std::function<std::vector<FilterStep>()> path) { filter_path_ = std::move(path); }
  /// The filter was moved by `correction` (x ↦ correction ⊕ x) at the newest node (feedback): its path changes
  /// frame there, which the motion edge into that node takes into account.
  void noteFilterCorrection(const Pose2& correction) { frame_changes_[nodes_.size() - 1] = correction; }

  /// `matched`: whether the filter's newest pose came from its scan match (false: drawn from the motion model).
  LoopClosureStep addScan(std::size_t scan_index, double timestamp, const Pose2& filter_pose, const Pose2& motion,
                          const Pose2* odometry, const PreparedScan& scan, bool matched = true);
  /// A closure from outside the search (a person's, a fiducial's, a test's): the newest node seen from node `from`
  /// at `z` (in `from`'s frame), with deviations `sigma_xy` (m) and `sigma_theta` (rad). It is judged as the
  /// windowed search's closures are: Huber loss, and left out when it still disagrees by more than
  /// `outlier_sigmas` after the next optimisation (due within `optimize_every` nodes). Before any addScan, or
  /// with `from` not older than the newest node: std::invalid_argument.
  void addExternalClosure(std::size_t from, const Pose2& z, double sigma_xy, double sigma_theta);
  /// The poses of the result: the graph with its motion edges re-derived from the filter's path and optimised
  /// once more (on a copy: the loop closure goes on as it was, and asking twice gives the same poses). Without a
  /// closure, the filter's path itself.
  std::vector<Pose2> finalPoses() const;

  std::size_t nodes() const { return nodes_.size(); }
  /// The optimised pose of every node, in processing order.
  std::vector<Pose2> poses() const;
  std::size_t scanIndexOf(std::size_t node) const { return nodes_[node].scan_index; }
  const std::vector<LoopClosureRecord>& closures() const { return closures_; }
  const PoseGraph& graph() const { return graph_; }
  const LoopClosureOptions& options() const { return o_; }
  LoopClosureCounts counts() const;

 private:
  struct Node {
    std::size_t scan_index;
    double timestamp;
    double travelled;             ///< m along the trajectory from the first node
    /// The filter's disagreement with the odometry summed over the suspect steps from the first node (m, rad).
    double suspect_xy = 0.0, suspect_theta = 0.0;
    std::vector<Point2> points;   ///< matching hits within point_range, robot frame, one per grid cell
    Point2 sensor;                ///< the laser's position in the robot frame (where the points' beams start)
    std::optional<Pose2> odometry;  ///< the odometry's motion since the previous node
    std::size_t motion_edge = 0;    ///< the edge from the previous node (none for the first)
  };
  struct Submap {
    std::size_t first, last;  ///< node range [first, last]
    /// Its points in the frame of its first node, fixed when it is first searched (then rigid): the grid is
    /// rebuilt from them whenever the cache dropped it, so the cache's size changes the memory, not the result.
    std::vector<Point2> points;
    bool frozen = false;
  };

  void addFilterMotion(std::size_t scan_index, double timestamp, const Pose2& filter_pose, const Pose2& motion,
                       const Pose2* odometry, const PreparedScan& scan, bool matched);
  void searchForClosures(LoopClosureStep& step, std::size_t node);
  /// The windowed search, again, for the nodes from backfill_from_ to before `newest` (a new loop closed).
  void backfillClosures(LoopClosureStep& step, std::size_t newest);
  /// Adds the closure edge from node `from` to `node` (z: node in from's frame) and its record.
  void addClosure(std::size_t from, std::size_t node, const Pose2& z, const Eigen::Matrix3d& sqrt_information,
                  double score, double window_xy, double offset_xy, double offset_theta, bool global);
  /// A stretch of trajectory: the nodes whose travel lies within [travel(centre) − back, travel(centre) + ahead].
  std::pair<std::size_t, std::size_t> stretchOf(std::size_t centre, double back, double ahead) const;
  /// The points of nodes [first, last] in the frame of node `centre`, thinned to one per `voxel`.
  /// The correlation grid a global query is matched against: the place's stretches global_query_m both ways.
  CorrelationGrid placeGrid(std::size_t place_node, const std::vector<Pose2>& geometry) const;
  /// What the same stretches saw (observed_area.h): a global match is judged on the query points inside it.
  ObservedArea placeObservedArea(std::size_t place_node, const std::vector<Pose2>& geometry) const;
  std::vector<Point2> stretchPoints(std::size_t centre, std::size_t first, std::size_t last,
                                    const std::vector<Pose2>& geometry, double voxel) const;
  PlaceSignatureShape signatureShape() const;
  void signOlderPlaces(const std::vector<Pose2>& geometry);
  /// Whether a windowed closure found from a node that had travelled at least since_travelled ties it to the
  /// submap or to one of its neighbours.
  bool closedRecently(std::size_t submap, double since_travelled) const;
  void proposeGlobalClosures(const std::vector<Pose2>& geometry);
  void verifyGlobalClosures(LoopClosureStep& step, const std::vector<Pose2>& geometry);
  /// The graph's poses from `place` on, with the error that the closure `z` (node in the place's frame) finds
  /// spread along the travel between them: the optimisation's starting point after a large correction.
  void distributeLoopError(std::size_t place, std::size_t node, const Pose2& z);
  /// A place of the trajectory: node `node` and the stretch of half global_query_m either side of it.
  struct SignedPlace {
    std::size_t node;
    PlaceSignature signature;
  };
  /// An exact match of a global search, waiting for agreement.
  struct GlobalMatch {
    std::size_t node, place;  ///< the query's middle node, the place's node
    Pose2 z;                  ///< the node in the place's frame
    Eigen::Matrix3d sqrt_information;
    double score, offset_xy, offset_theta;
    bool accepted = false;
  };
  /// The two matches agree: the loop they close with the trajectory between their queries and between their
  /// places closes within the tolerance (false when either stretch is too long to compare).
  bool globalMatchesAgree(const GlobalMatch& a, const GlobalMatch& b, const std::vector<Pose2>& geometry) const;
  /// How far the graph's motion edges can have drifted between two nodes, each the least over the graph's paths
  /// (motion edges count, accepted closures are free): the travel (m), and the filter's disagreement with the
  /// odometry summed over the suspect steps (m, rad), where one of the two went wrong.
  struct PathDrift {
    double travel, suspect_xy, suspect_theta;
  };
  /// The windowed search's half-width for a path with this drift, before the window_xy_max cap.
  double driftWindowXy(const PathDrift& p) const;
  /// Per submap, the drift from node `from` to the submap's nearest node.
  std::vector<PathDrift> driftToSubmaps(std::size_t from) const;
  /// A global query: its points (in its middle node's frame), the copy the branch and bound scores (thinned to
  /// global_search_voxel when `thinned`) and the heading step of its refinement.
  struct GlobalQuery {
    std::size_t node = 0;
    std::vector<Point2> points, search_points;
    double dtheta = 0.0;
    bool thinned = false;
  };
  /// The exact match of query `q` against the stretches of place node `place` within `window` (the query in the
  /// place's frame), judged by its plain score (min_score), by what the place saw, by ambiguity and by the
  /// trajectory's bounds; a surviving match waits for agreement in pending_ (true).
  bool matchGlobally(const GlobalQuery& q, std::size_t place, const SearchWindow& window, double min_score,
                     const std::vector<PathDrift>& drift, const std::vector<Pose2>& geometry);
  /// How far (m, rad) a match of the query at node `node` to place node `place` may move the query from where the
  /// graph puts it: the drift the graph's least-drift path between them can have gathered.
  struct DriftBound {
    double xy, theta;
  };
  DriftBound driftBound(std::size_t place, const std::vector<PathDrift>& drift) const;
  /// Whether every match matchGlobally can return within `window` (the window plus the refinement's longest climb)
  /// lies beyond `bound` (driftBound), so that the match would be refused whatever the place's grid holds.
  bool beyondDriftBound(const GlobalQuery& q, std::size_t place, const SearchWindow& window,
                        const DriftBound& bound) const;
  /// Whether the windowed search reaches place node `place` from node `node` and has just closed it.
  bool leftToWindowedSearch(std::size_t place, std::size_t node, const std::vector<PathDrift>& drift) const;
  /// Where the newest match waiting for agreement puts node `node`: the node of its place's pass nearest to it
  /// (none older than travel `latest`; nothing when all are further than half a view) and `node`'s pose in that
  /// node's frame.
  std::optional<std::pair<std::size_t, Pose2>> predictedPlace(std::size_t node, double latest,
                                                              const std::vector<Pose2>& geometry) const;
  /// The square-root information of a match of `query` at `x` in `grid`, from the curvature of its score.
  Eigen::Matrix3d closureSqrtInformation(const CorrelationGrid& grid, const std::vector<Point2>& query,
                                         const Pose2& x, double dtheta) const;
  /// The motion edge from node `prev` to the next: `motion` with a deviation widened by a disagreement with the
  /// odometry beyond the motion model's noise, and by the motion model's deviations where the match failed.
  PoseGraphEdge motionEdge(std::size_t prev, const Pose2& motion, const Pose2* odometry, bool matched) const;
  /// The motion edges re-derived from the filter's current best path (filter_path_), whose history resampling
  /// has pruned of the lineages that died out; without closures the nodes take its poses.
  void adoptFilterPath();
  /// The motion edges of `g` from the filter path `path` (one pose per node; frame changes of feedback applied).
  void setMotionEdges(const std::vector<FilterStep>& path, PoseGraph& g) const;
  /// The poses of a filter path.
  static std::vector<Pose2> posesOf(const std::vector<FilterStep>& path);
  /// How far the filter's motion and the odometry's differ (m, rad), on a suspect step: one where they differ by
  /// more than disagreement_sigmas motion-model deviations (Mahalanobis). None on other steps or without odometry.
  struct Disagreement {
    double xy, theta;
  };
  std::optional<Disagreement> suspectDisagreement(const Pose2& motion, const Pose2* odometry) const;
  PoseGraphSolveOptions solveOptions() const;
  void optimizePoseGraph(LoopClosureStep& step);
  /// The poses that place the scans of a query or a submap relative to each other: the filter's current best
  /// path when there is one (one particle's history, consistent step after step), else the graph's poses (whose
  /// newest steps were added from whichever particle was best at the time).
  std::vector<Pose2> localGeometry() const;
  std::vector<Point2> queryOf(std::size_t node, const std::vector<Pose2>& geometry) const;
  const CorrelationGrid& gridOf(std::size_t submap, const std::vector<Pose2>& geometry);

  LoopClosureOptions o_;
  OdometryMotionModel motion_;
  std::function<std::vector<FilterStep>()> filter_path_;
  std::map<std::size_t, Pose2> frame_changes_;  ///< node -> the correction applied to the filter at it
  PoseGraph graph_;
  std::vector<Node> nodes_;
  std::vector<Submap> submaps_;
  std::vector<LoopClosureRecord> closures_;
  std::size_t pending_from_ = 0;        ///< closures_[pending_from_..] not yet optimised
  std::size_t last_optimized_node_ = 0;
  // Correlation grids, least recently used last.
  std::list<std::pair<std::size_t, std::unique_ptr<CorrelationGrid>>> cache_;
  std::size_t searches_ = 0, ambiguous_ = 0, border_ = 0, suspect_ = 0, optimizations_ = 0;
  // The global search.
  std::vector<SignedPlace> places_;
  std::size_t next_to_sign_ = 0;
  double last_signed_travel_ = -1e300, last_global_travel_ = -1e300;
  std::vector<GlobalMatch> pending_;
  bool optimize_now_ = false;
  std::size_t backfill_from_ = static_cast<std::size_t>(-1);  ///< nodes the windowed search revisits (a new loop)
  std::size_t global_searches_ = 0, global_proposed_ = 0, global_contradicted_ = 0, global_dropped_ = 0,
              global_refuted_ = 0, global_followed_ = 0, global_beyond_bound_ = 0;
  double cpu_windowed_ = 0.0, cpu_global_sign_ = 0.0, cpu_global_query_ = 0.0, cpu_global_verify_ = 0.0,
         cpu_optimize_ = 0.0;
};

/// The text of the closures table of stats.txt ("# closures" header, one row per closure, rejected ones too), then
/// the summary line "# loop_closure: ..." with `counts` and the number of feedbacks (no times: stats.txt's other
/// lines are the same for a seed whatever the machine, but for their time and RSS columns).
std::string closuresText(const std::vector<LoopClosureRecord>& closures, const LoopClosureCounts& counts,
                         std::size_t feedbacks);

/// The line "# loop_closure_cpu_seconds: ..." of stats.txt: the processor seconds of the loop closure's parts
/// (LoopClosureCounts::cpu_*), which differ from run to run.
std::string loopClosureCpuText(const LoopClosureCounts& counts);

}  // namespace gridtopo::slam
