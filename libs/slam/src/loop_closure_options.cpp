#include "gridtopo/slam/loop_closure_options.h"

namespace gridtopo::slam {

const OptionSchema<LoopClosureOptions>& loopClosureOptionSchema() {
  using O = LoopClosureOptions;
  using R = OptionRange;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::slam::LoopClosureOptions")
          .add("enabled", &O::enabled, R::any(), "", "pose graph with loop closures over the filter (false: the filter alone)")
          .add("submap_nodes", &O::submap_nodes, R::closed(1, 1000), "", "processed scans per submap")
          .add("point_range", &O::point_range, R::above(0), "m", "hits further from their scan are not matched")
          .add("query_nodes", &O::query_nodes, R::closed(1, 100), "", "newest processed scans that form the query")
          .add("query_voxel", &O::query_voxel, R::above(0), "m", "the query is thinned to a point per voxel")
          .add("resolution", &O::resolution, R::closed(0.005, 1), "m", "cell of the correlation grids")
          .add("field_sigma", &O::field_sigma, R::above(0), "m", "width of the grid's value around a hit")
          .add("refine_sigma", &O::refine_sigma, R::above(0), "m", "width of the refinement's value around a hit")
          .add("depth", &O::depth, R::closed(0, 12), "", "branch-and-bound levels (coarsest: 2^depth cells)")
          .add("grid_cache", &O::grid_cache, R::closed(1, 10000), "", "correlation grids kept in memory")
          .add("search_every", &O::search_every, R::closed(1, 100000), "", "search at every n-th processed scan")
          .add("min_travel", &O::min_travel, R::atLeast(0), "m", "travel since a submap before it is searched")
          .add("max_candidates", &O::max_candidates, R::closed(1, 1000), "", "submaps searched per search")
          .add("window_xy_min", &O::window_xy_min, R::atLeast(0), "m", "search half-width at no drift")
          .add("window_xy_per_m", &O::window_xy_per_m, R::atLeast(0), "m/m",
               "its growth per metre of the graph's path to the submap")
          .add("window_xy_max", &O::window_xy_max, R::atLeast(0), "m", "its largest value")
          .add("window_theta_min", &O::window_theta_min, R::closed(0, 3.14), "rad", "heading half-width at no drift")
          .add("window_theta_per_m", &O::window_theta_per_m, R::atLeast(0), "rad/m", "its growth per metre")
          .add("window_theta_max", &O::window_theta_max, R::closed(0, 3.14), "rad", "its largest value")
          .add("min_score", &O::min_score, R::closed(0, 1), "", "a match's mean grid value must reach this")
          .add("ambiguity_ratio", &O::ambiguity_ratio, R::leftOpen(0, 1), "",
               "refuse a match when another pose scores this fraction of it (1: never refuse)")
          .add("ambiguity_distance", &O::ambiguity_distance, R::above(0), "m", "how far that other pose must be")
          .add("global_search", &O::global_search, R::any(), "", "propose closures anywhere by place signatures, verified by agreement (false: the windowed search alone)")
          .add("global_every_m", &O::global_every_m, R::above(0), "m", "travel between global searches")
          .add("global_query_m", &O::global_query_m, R::above(0), "m", "trajectory behind a pose that forms its place")
          .add("global_signature_every_m", &O::global_signature_every_m, R::above(0), "m", "travel between signed poses")
          .add("global_min_travel", &O::global_min_travel, R::atLeast(0), "m", "travel between a place and a query")
          .add("global_candidates", &O::global_candidates, R::closed(1, 100), "", "places matched exactly per global search")
          .add("global_max_distance", &O::global_max_distance, R::closed(0, 1), "", "largest signature distance of a candidate")
          .add("global_window_xy", &O::global_window_xy, R::above(0), "m", "exact search half-width around a candidate")
          .add("global_window_theta", &O::global_window_theta, R::closed(0, 3.14), "rad", "its heading half-width")
          .add("global_min_score", &O::global_min_score, R::closed(0, 1), "", "a global match's mean grid value over all its points")
          .add("global_min_observed", &O::global_min_observed, R::closed(0, 1), "", "... over its points the place saw")
          .add("global_max_contradiction", &O::global_max_contradiction, R::closed(0, 1), "", "largest share of its points in space the place saw free")
          .add("global_follow_min_score", &O::global_follow_min_score, R::closed(0, 1), "", "a query matched where a waiting match predicts it: its mean grid value over all its points")
          .add("global_search_voxel", &O::global_search_voxel, R::atLeast(0), "m", "the branch and bound of a global match thins its query to a point per voxel this size (0: every point)")
          .add("global_prejudge", &O::global_prejudge, R::any(), "", "skip a candidate whose whole search window lies beyond the drift bound (false: match it anyway; the same closures, slower)")
          .add("global_agree", &O::global_agree, R::closed(1, 100), "", "agreeing independent matches before a global closure is accepted")
          .add("global_independent_m", &O::global_independent_m, R::atLeast(0), "m", "travel between independent matches")
          .add("global_consistency_xy", &O::global_consistency_xy, R::above(0), "m", "two matches agree within this")
          .add("global_consistency_theta", &O::global_consistency_theta, R::above(0), "rad", "... and this heading")
          .add("global_consistency_per_m", &O::global_consistency_per_m, R::atLeast(0), "m/m", "... plus this per metre of the loop's trajectory")
          .add("global_consistency_max_m", &O::global_consistency_max_m, R::above(0), "m", "matches further apart are not compared")
          .add("global_pending_m", &O::global_pending_m, R::above(0), "m", "travel a match waits for agreement")
          .add("signature_rings", &O::signature_rings, R::closed(2, 200), "", "place signature's radial bins")
          .add("signature_sectors", &O::signature_sectors, R::closed(8, 720), "", "place signature's angular bins")
          .add("information_gain", &O::information_gain, R::above(0), "",
               "a closure's information: its score's curvature over the query's points divided by this")
          .add("loop_sigma_xy", &O::loop_sigma_xy, R::above(0), "m", "floor of a closure's translation deviation")
          .add("loop_sigma_theta", &O::loop_sigma_theta, R::above(0), "rad", "floor of a closure's heading deviation")
          .add("odometry_sigma_xy", &O::odometry_sigma_xy, R::above(0), "m", "floor of a motion edge's deviation")
          .add("odometry_sigma_xy_per_m", &O::odometry_sigma_xy_per_m, R::atLeast(0), "m/m", "its growth with the motion")
          .add("odometry_sigma_theta", &O::odometry_sigma_theta, R::above(0), "rad", "heading floor")
          .add("odometry_sigma_theta_per_rad", &O::odometry_sigma_theta_per_rad, R::atLeast(0), "rad/rad",
               "its growth with the rotation")
          .add("huber_scale", &O::huber_scale, R::above(0), "sigma", "closures' Huber loss scale")
          .add("outlier_sigmas", &O::outlier_sigmas, R::atLeast(0), "sigma",
               "reject a new closure still this far off after the optimisation (0 = keep all)")
          .add("disagreement_sigmas", &O::disagreement_sigmas, R::atLeast(0), "sigma",
               "filter vs odometry disagreement (motion-model deviations) above which a step is suspect")
          .add("unmatched_steps_as_odometry", &O::unmatched_steps_as_odometry, R::any(), "",
               "a step whose scan match failed gets the motion model's deviations")
          .add("optimize_every", &O::optimize_every, R::closed(1, 1000000), "", "processed scans between optimisations")
          .add("max_iterations", &O::max_iterations, R::closed(1, 10000), "", "solver iterations per optimisation")
          .add("feedback", &O::feedback, R::any(), "", "the particles continue from the optimised poses and map")
          .add("feedback_min_correction", &O::feedback_min_correction, R::atLeast(0), "m",
               "feed back only corrections larger than this")
          .add("feedback_min_rotation", &O::feedback_min_rotation, R::atLeast(0), "rad", "... or this rotation");
  return schema;
}

}  // namespace gridtopo::slam
