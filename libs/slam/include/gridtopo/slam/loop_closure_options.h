#pragma once
// Every tunable of the loop closure (a pose graph over the filter's trajectory, loop_closure.h), loadable from
// its own INI section [loop_closure] through one key table (loopClosureOptionSchema). `enabled = false` gives the
// filter alone. config-ini/slam.ini documents each key.
#include "gridtopo/core/option_schema.h"

namespace gridtopo::slam {

struct LoopClosureOptions;
/// The key table of [loop_closure].
const OptionSchema<LoopClosureOptions>& loopClosureOptionSchema();

struct LoopClosureOptions : TableOptions<LoopClosureOptions, loopClosureOptionSchema> {
  static constexpr const char* kSection = "loop_closure";
  bool enabled = true; ///< false: the filter alone (its best particle's trajectory and map)

  // Submaps and the query
  int submap_nodes = 20;        ///< consecutive processed scans per submap
  double point_range = 15.0;    ///< m, hits further from their scan's pose are not used for matching
  int query_nodes = 5;          ///< the newest processed scans whose points, in the newest's frame, form the query
  double query_voxel = 0.1;     ///< m, the query's points are thinned to one per voxel of this size
  double resolution = 0.05;     ///< m, cell of the submaps' correlation grids
  double field_sigma = 0.07;    ///< m, the grid's value falls as exp(−d²/2σ²) with the distance d to a hit
  double refine_sigma = 0.03;   ///< m, the same for the refinement of a match (sharper: a precise pose)
  int depth = 7;                ///< levels of the branch-and-bound precomputation (the coarsest spans 2^depth cells)
  int grid_cache = 6;           ///< correlation grids kept (least recently used dropped)

  // When and where to search
  int search_every = 2;         ///< search at every n-th processed scan
  double min_travel = 5.0;      ///< m travelled since a submap's last scan before it is a candidate
  int max_candidates = 3;       ///< submaps searched per search, nearest first (in units of their reach)
  double window_xy_min = 1.0;   ///< m, search half-width of a submap the graph's path reaches without drift
  /// m of half-width per m of travel along the graph's shortest path to the submap (accepted closures cost nothing)
  double window_xy_per_m = 0.05;
  double window_xy_max = 8.0;       ///< m
  double window_theta_min = 0.1;    ///< rad
  double window_theta_per_m = 0.004;  ///< rad per m of the same path
  double window_theta_max = 0.5;    ///< rad
  double min_score = 0.55;      ///< mean grid value over the query's points a match must reach
  /// A match is refused as ambiguous when a pose further than ambiguity_distance from it scores at least
  /// ambiguity_ratio times its score (look-alike corridors, a corridor's own length).
  double ambiguity_ratio = 0.93;
  double ambiguity_distance = 0.6;  ///< m

  // Global closures: proposed anywhere in the map, whatever the drift, and verified before they bend it
  /// true: besides the windowed search above, places are proposed by their signature (place_signature.h) among
  /// every older stretch of the trajectory, matched exactly, and enter the graph only once several independent
  /// matches agree with each other and with the trajectory between them. false: the windowed search alone.
  bool global_search = true;
  double global_every_m = 2.0;     ///< m of travel between global searches
  double global_query_m = 20.0;    ///< m of trajectory behind a pose whose points form its place (query and signature)
  double global_signature_every_m = 1.0;  ///< m of travel between the older poses that get a signature
  double global_min_travel = 30.0;  ///< m of travel between a place and the query before it is a candidate
  int global_candidates = 3;        ///< places matched exactly per global search, best signatures first
  double global_max_distance = 0.75; ///< a candidate's signature distance must be below this (0: identical, 1: unlike)
  double global_window_xy = 3.0;    ///< m, half-width of the exact search around the signature's place
  double global_window_theta = 0.2;  ///< rad, half-width around the signature's heading
  /// The exact match's mean grid value over all the query's points. Points where the place never looked lower it
  /// without contradicting anything, so this bar is low; the next two judge the match where the place looked.
  double global_min_score = 0.40;
  /// The mean grid value over the query's points that fall where the place's scans saw (observed_area.h).
  double global_min_observed = 0.50;
  /// The largest share of the query's points that may fall in space the place's beams saw free.
  double global_max_contradiction = 0.10;
  /// A match waiting for agreement predicts where each later query lies in its place's pass; the query is matched
  /// there first, within the windowed search's smallest window, to this plain score (the last two bars unchanged).
  double global_follow_min_score = 0.25;
  /// m: the branch and bound of a global match scores the query thinned to one point per voxel of this size (its
  /// refinement and final score use every point); 0: every point throughout.
  double global_search_voxel = 0.3;
  /// true: a candidate whose whole search window (with the refinement's longest climb) lies beyond the drift bound
  /// the match would be judged by is not matched (it could only be refused: the same closures, without its grid
  /// and search). false: every candidate is matched (slower; for checking that the two agree).
  bool global_prejudge = true;
  /// Matches (this one included) whose queries lie at least global_independent_m apart that must agree before any
  /// of them enters the graph. Queries share most of their points (each is global_query_m long): 8 m apart they
  /// share three fifths, 4 m apart four fifths, and the same look-alike corner in all of them is one piece of
  /// evidence, not three (the simulated 1 km ring, queries every 2 m: at 4 or 6 m a false corner-to-corner clique
  /// is accepted).
  int global_agree = 3;
  double global_independent_m = 8.0;
  /// Two matches agree when the loop they close with the trajectory between their queries and between their places
  /// closes within global_consistency_xy (m) + global_consistency_per_m × that trajectory's length, and
  /// global_consistency_theta (rad) + a tenth of that per metre; places or queries further apart than
  /// global_consistency_max_m along the trajectory are not compared.
  double global_consistency_xy = 0.3;
  double global_consistency_theta = 0.03;
  double global_consistency_per_m = 0.01;
  double global_consistency_max_m = 80.0;
  double global_pending_m = 60.0;   ///< m of travel a match waits for agreement before it is dropped
  int signature_rings = 15;         ///< the signature's radial bins over point_range
  int signature_sectors = 72;       ///< its angular bins

  // The pose graph
  /// A closure's information is the curvature of its match's score (each query point one observation, divided by
  /// information_gain for the correlation between neighbouring points), its deviations floored at loop_sigma_*.
  double information_gain = 1.0;
  double loop_sigma_xy = 0.05;      ///< m, floor of a closure's translation deviation
  double loop_sigma_theta = 0.0125;  ///< rad, floor of its heading deviation
  double odometry_sigma_xy = 0.003;  ///< m, floor of a filter motion edge's deviation (added to the proposal's)
  double odometry_sigma_xy_per_m = 0.005;  ///< m per m of the motion
  double odometry_sigma_theta = 0.0007;   ///< rad, floor
  double odometry_sigma_theta_per_rad = 0.005;  ///< rad per rad of rotation
  double huber_scale = 3.0;     ///< closures' robust loss: Huber, in standard deviations
  /// After an optimisation, a new closure whose whitened residual is still above this (standard deviations) is
  /// rejected: it disagrees with the filter's motion and the other closures (a look-alike place), and the graph is
  /// optimised again without it. 0 = keep every closure.
  double outlier_sigmas = 4.0;
  /// A step where the filter's motion and the odometry's differ by more than this many deviations of the motion
  /// model (Mahalanobis) is suspect: its motion edge is weakened by the difference, and the difference widens the
  /// search window of every path through it. Below it, the disagreement is odometry noise and the edge stays stiff.
  double disagreement_sigmas = 3.0;
  /// A step where the best particle's scan match failed (its pose drawn from the odometry motion model, not from
  /// the match) is as uncertain as the motion model says: its motion edge takes the model's deviations for the
  /// step (in quadrature with the filter's own). false (the default): every motion edge as stiff as a matched one.
  /// On, the campus holds with 20 particles and the hospital improves, but a weak wrong closure at the window's
  /// edge bends a soft stretch of the campus with 30 (doc/journal/2026-12-07-unmatched-steps.md).
  bool unmatched_steps_as_odometry = false;
  int optimize_every = 15;      ///< processed scans between optimisations (when a closure was added since)
  int max_iterations = 30;      ///< solver iterations per optimisation

  // Feeding back into the filter
  /// After an optimisation that moves the newest pose by more than feedback_min_correction (m) or
  /// feedback_min_rotation (rad), every particle continues from the optimised poses: its map rebuilt from the
  /// graph, its pose moved by the same correction.
  bool feedback = false;
  double feedback_min_correction = 0.10;
  double feedback_min_rotation = 0.02;
};

}  // namespace gridtopo::slam
