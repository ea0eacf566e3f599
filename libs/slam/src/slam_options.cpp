#include "gridtopo/slam/slam_options.h"

#include <mrpt/config/CConfigFileBase.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/core/error.h"

namespace gridtopo::slam {

namespace {

using R = OptionRange;
using O = SlamOptions;

/// The proposal words: the INI key `proposal`, --proposal, toString and proposalFromString.
const std::vector<std::pair<std::string, ProposalType>>& proposalWords() {
  static const std::vector<std::pair<std::string, ProposalType>> words{{"informed", ProposalType::Informed},
                                                                       {"mode-only", ProposalType::ModeOnly},
                                                                       {"hahnel", ProposalType::Hahnel},
                                                                       {"odometry", ProposalType::Odometry}};
  return words;
}

OptionSchema<SlamOptions> makeSchema() {
  OptionSchema<SlamOptions> s("gridtopo::slam::SlamOptions");
  // Filter
  s.add("particles", &O::particles, R::closed(1, 100000), "", "number of particles");
  s.add("seed", &O::seed, R::any(), "", "random seed (the output is identical for a seed whatever the threads)");
  s.add("threads", &O::threads, R::atLeast(0), "", "worker threads, 0 = all cores");
  s.add("resample_threshold", &O::resample_threshold, R::closed(0, 1), "",
        "resample when N_eff < resample_threshold * particles");
  s.add("min_particles", field(&O::kld, &KldOptions::min_particles), R::atLeast(0), "",
        "adaptive particle set: the fewest particles after a resampling (KLD-sampling, Fox 2003; 0 = always "
        "`particles`, which is then the maximum)");
  s.add("kld_epsilon", field(&O::kld, &KldOptions::epsilon), R::above(0), "",
        "KLD-sampling: bound on the KL distance between the particles and the binned posterior");
  s.add("kld_z", field(&O::kld, &KldOptions::z), R::above(0), "",
        "KLD-sampling: upper 1 - delta quantile of the standard normal (2.326: delta = 0.01)");
  s.add("kld_bin_xy", field(&O::kld, &KldOptions::bin_xy), R::above(0), "m", "KLD-sampling: histogram bin size in x and y");
  s.add("kld_bin_theta", field(&O::kld, &KldOptions::bin_theta), R::above(0), "rad",
        "KLD-sampling: histogram bin size in heading");
  s.add("kld_grow_failed_fraction", field(&O::kld, &KldOptions::grow_failed_fraction), R::atLeast(0), "",
        "adaptive particle set: resample to `particles` at once when this share of the matches failed at a step "
        "(> 1: never)");
  s.add("likelihood_gain", &O::likelihood_gain, R::above(0), "",
        "the observation log-likelihood is divided by this (softens the independent-beam model)");
  // Update policy
  s.add("linear_update", &O::linear_update, R::atLeast(0), "m", "process a scan after this travelled distance");
  s.add("angular_update", &O::angular_update, R::atLeast(0), "rad", "... or after this accumulated rotation");
  s.add("temporal_update", &O::temporal_update, R::any(), "s", "... or after this time; < 0: never on time alone");
  s.add("no_odometry_period", &O::no_odometry_period, R::atLeast(0), "s",
        "logs without odometry: process a scan after this time (0 = every scan)");
  s.add("resolution", &O::resolution, R::leftOpen(0, 10), "m", "cell size of the map");
  // Motion model
  s.add("motion_alpha_rr", field(&O::motion, &MotionModelOptions::alpha_rr), R::atLeast(0), "rad^2/rad^2",
        "rotation noise from rotation");
  s.add("motion_alpha_rt", field(&O::motion, &MotionModelOptions::alpha_rt), R::atLeast(0), "rad^2/m^2",
        "rotation noise from translation");
  s.add("motion_alpha_tt", field(&O::motion, &MotionModelOptions::alpha_tt), R::atLeast(0), "m^2/m^2",
        "translation noise from translation");
  s.add("motion_alpha_tr", field(&O::motion, &MotionModelOptions::alpha_tr), R::atLeast(0), "m^2/rad^2",
        "translation noise from rotation");
  s.add("motion_min_sigma_xy", field(&O::motion, &MotionModelOptions::min_sigma_xy), R::above(0), "m",
        "translation noise floor, added in quadrature");
  s.add("motion_min_sigma_theta", field(&O::motion, &MotionModelOptions::min_sigma_theta), R::above(0), "rad",
        "rotation noise floor, added in quadrature");
  s.add("no_odometry_sigma_xy", field(&O::motion, &MotionModelOptions::no_odometry_sigma_xy), R::above(0), "m",
        "motion prior of scans without odometry: zero motion with this deviation");
  s.add("no_odometry_sigma_theta", field(&O::motion, &MotionModelOptions::no_odometry_sigma_theta), R::above(0), "rad",
        "the same for the heading");
  s.add("motion_scale_sigma", field(&O::motion, &MotionModelOptions::scale_sigma), R::closed(0, 0.2), "",
        "odometry scale per particle: initial deviation of the factor (0 = off)");
  s.add("motion_scale_walk_sigma", field(&O::motion, &MotionModelOptions::scale_walk_sigma), R::closed(0, 0.2),
        "1/sqrt(m)", "odometry scale per particle: random walk of the factor per metre (0 = off)");
  // Map
  s.add("map_log_odds_hit", field(&O::map, &MapUpdateOptions::log_odds_hit), R::above(0), "",
        "log-odds added where a beam ends");
  s.add("map_log_odds_free", field(&O::map, &MapUpdateOptions::log_odds_free), R::below(0), "",
        "log-odds added in every cell a beam crosses");
  s.add("map_log_odds_min", field(&O::map, &MapUpdateOptions::log_odds_min), R::below(0), "", "lower clamp of a cell");
  s.add("map_log_odds_max", field(&O::map, &MapUpdateOptions::log_odds_max), R::above(0), "", "upper clamp of a cell");
  // Beams
  s.add("max_usable_range", field(&O::beams, &BeamOptions::max_usable_range), R::atLeast(0), "m",
        "returns at or beyond this range clear free space but mark no obstacle; 0 = the sensor's max range");
  s.add("min_range", field(&O::beams, &BeamOptions::min_range), R::atLeast(0), "m", "closer returns are ignored");
  s.add("clear_no_return", field(&O::beams, &BeamOptions::clear_no_return), R::any(), "",
        "no-return readings clear free space up to no_return_range (REP-117)");
  s.add("no_return_range", field(&O::beams, &BeamOptions::no_return_range), R::atLeast(0), "m",
        "free space cleared by a no-return reading");
  s.add("matching_beam_step", field(&O::beams, &BeamOptions::matching_beam_step), R::atLeast(0), "",
        "match every n-th hit beam; 0 = from matching_beam_angle");
  s.add("matching_beam_angle", field(&O::beams, &BeamOptions::matching_beam_angle), R::above(0), "rad",
        "matching_beam_step = 0: spacing of the matching beams");
  s.add("matching_range_margin", field(&O::beams, &BeamOptions::matching_range_margin), R::atLeast(0), "m",
        "hits within this of the usable range are inserted but not matched");
  s.add("matching_min_incidence", field(&O::beams, &BeamOptions::matching_min_incidence), R::rightOpen(0, 1.5), "rad",
        "hits meeting the surface at a smaller angle are not matched (0 = match all)");
  s.add("map_surface_clearance", field(&O::beams, &BeamOptions::surface_clearance), R::atLeast(0), "m",
        "a beam does not clear cells this close to the surface it hit (0 = off)");
  // Scan matcher
  s.add("match_sigma", field(&O::matcher, &ScanMatcherOptions::sigma), R::above(0), "m",
        "deviation of the end point to obstacle distance");
  s.add("match_kernel", field(&O::matcher, &ScanMatcherOptions::kernel), R::closed(0, 5), "cells",
        "correspondence search window half size");
  s.add("match_null_log_likelihood", field(&O::matcher, &ScanMatcherOptions::null_log_likelihood), R::below(0), "",
        "per-beam log-likelihood floor (no correspondence)");
  s.add("match_occupied_log_odds", field(&O::matcher, &ScanMatcherOptions::occupied_log_odds), R::any(), "",
        "a cell is a correspondence candidate above this log-odds; in [map_log_odds_min, map_log_odds_max)");
  s.add("match_free_check", field(&O::matcher, &ScanMatcherOptions::free_check), R::any(), "",
        "GMapping's 'cell in front must be free' test");
  s.add("match_use_motion_prior", field(&O::matcher, &ScanMatcherOptions::use_motion_prior), R::any(), "",
        "climb to the mode of the likelihood times the motion prior (false: the likelihood alone)");
  s.add("match_gn_iterations", field(&O::matcher, &ScanMatcherOptions::gn_iterations), R::atLeast(0), "",
        "gauss-newton: iterations");
  s.add("match_gn_kernel", field(&O::matcher, &ScanMatcherOptions::gn_kernel), R::closed(0, 5), "cells",
        "gauss-newton: correspondence window half size");
  s.add("match_polish_step_xy", field(&O::matcher, &ScanMatcherOptions::polish_step_xy), R::above(0), "m",
        "gauss-newton: first step of the hill-climbing polish");
  s.add("match_polish_step_theta", field(&O::matcher, &ScanMatcherOptions::polish_step_theta), R::above(0), "rad",
        "gauss-newton: first heading step of the polish");
  s.add("match_polish_refinements", field(&O::matcher, &ScanMatcherOptions::polish_refinements), R::atLeast(0), "",
        "gauss-newton: step halvings of the polish");
  s.add("match_step_xy", field(&O::matcher, &ScanMatcherOptions::step_xy), R::above(0), "m",
        "hill climbing: first step in x and y");
  s.add("match_step_theta", field(&O::matcher, &ScanMatcherOptions::step_theta), R::above(0), "rad",
        "hill climbing: first heading step");
  s.add("match_refinements", field(&O::matcher, &ScanMatcherOptions::refinements), R::atLeast(0), "",
        "hill climbing: step halvings");
  s.add("match_coarse_levels", field(&O::matcher, &ScanMatcherOptions::coarse_levels), R::atLeast(0), "",
        "the first step sizes that score only every match_coarse_beam_step-th beam (0 = off)");
  s.add("match_coarse_beam_step", field(&O::matcher, &ScanMatcherOptions::coarse_beam_step), R::atLeast(1), "",
        "beam step of the coarse levels");
  s.add("match_max_iterations", field(&O::matcher, &ScanMatcherOptions::max_iterations), R::atLeast(1), "",
        "hill climbing: most moves");
  s.add("match_min_fraction", field(&O::matcher, &ScanMatcherOptions::min_match_fraction), R::closed(0, 1), "",
        "matching fails (odometry proposal) below this fraction of beams with a correspondence");
  // Informed proposal
  s.add("proposal_points_per_axis", field(&O::proposal, &ProposalOptions::points_per_axis), R::closed(2, 9), "",
        "K = points_per_axis^3 poses around the mode");
  s.add("proposal_delta_xy", field(&O::proposal, &ProposalOptions::delta_xy), R::above(0), "m",
        "spacing of the K poses in x and y");
  s.add("proposal_delta_theta", field(&O::proposal, &ProposalOptions::delta_theta), R::above(0), "rad",
        "spacing of the K poses in heading");
  s.add("proposal_min_sigma_xy", field(&O::proposal, &ProposalOptions::min_sigma_xy), R::atLeast(0), "m",
        "floor on the proposal's deviation in x and y");
  s.add("proposal_min_sigma_theta", field(&O::proposal, &ProposalOptions::min_sigma_theta), R::atLeast(0), "rad",
        "floor on the proposal's heading deviation");
  s.add("proposal_laplace_weight", field(&O::proposal, &ProposalOptions::laplace_weight), R::any(), "",
        "moments fit: Laplace approximation of the weight (false: Riemann sum over the K poses)");
  s.add("proposal_start_spread", field(&O::proposal, &ProposalOptions::start_spread), R::atLeast(0), "",
        "mode search starts at the prediction plus k times a motion-noise draw (0 = the prediction)");
  s.add("proposal_max_motion_sigmas", field(&O::proposal, &ProposalOptions::max_motion_sigmas), R::atLeast(0),
        "sigma", "matching fails when the mode lies further from the odometry's prediction (0 = no bound)");
  s.add("proposal_weak_match_fraction", field(&O::proposal, &ProposalOptions::weak_match_fraction), R::closed(0, 1),
        "", "proposal_max_motion_sigmas bounds only matches with fewer beams in correspondence than this fraction");
  s.add("proposal_report_mean", field(&O::proposal, &ProposalOptions::report_mean), R::any(), "",
        "trajectory poses are the proposal means (false: the samples)");
  s.add("proposal_beam_sigma", field(&O::proposal, &ProposalOptions::beam_sigma), R::above(0), "m",
        "quadratic fit: registration precision of one beam end point");
  s.add("proposal_min_curvature", field(&O::proposal, &ProposalOptions::min_curvature), R::atLeast(0), "nats",
        "quadratic fit: flatter directions follow the motion model");
  // Keys whose value is one of a few words
  s.addWords("proposal", field(&O::proposal, &ProposalOptions::type), proposalWords(),
             "informed (the paper's), mode-only (GMapping), hahnel, odometry (classic SIR)");
  s.addWords("proposal_fit", field(&O::proposal, &ProposalOptions::fit),
             {{"quadratic", ProposalFit::Quadratic}, {"moments", ProposalFit::Moments}},
             "how the proposal is fitted to the K poses");
  s.addWords("proposal_weight", field(&O::proposal, &ProposalOptions::weight),
             {{"mode", ProposalWeight::Mode}, {"integral", ProposalWeight::Integral}},
             "quadratic fit: weight factor from the likelihood at the mode or the Laplace integral");
  s.addWords("match_method", field(&O::matcher, &ScanMatcherOptions::method),
             {{"hill-climb", MatchMethod::HillClimb}, {"gauss-newton", MatchMethod::GaussNewton}},
             "scan matcher search");
  s.addWords("match_residual", field(&O::matcher, &ScanMatcherOptions::residual),
             {{"point", MatchResidual::Point}, {"plane", MatchResidual::Plane}},
             "end point distance to the hit mean (point) or along the surface normal (plane)");
  s.rule("match_occupied_log_odds", [](const O& o) -> std::optional<std::string> {
    if (o.matcher.occupied_log_odds >= o.map.log_odds_min && o.matcher.occupied_log_odds < o.map.log_odds_max)
      return std::nullopt;
    return "must lie in [map_log_odds_min, map_log_odds_max)";
  });
  return s;
}

}  // namespace

const OptionSchema<SlamOptions>& slamOptionSchema() {
  static const OptionSchema<SlamOptions> schema = makeSchema();
  return schema;
}

const char* toString(ProposalType t) {
  for (const auto& [word, value] : proposalWords())
    if (value == t) return word.c_str();
  return "?";
}

ProposalType proposalFromString(const std::string& s) {
  std::string all;
  for (const auto& [word, value] : proposalWords()) {
    if (s == word) return value;
    all += (all.empty() ? "" : ", ") + word;
  }
  throw std::invalid_argument("unknown proposal '" + s + "' (expected " + all + ")");
}

void SlamOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) {
  slamOptionSchema().load(*this, source, section);
  loop_closure.loadFromConfigFile(source, LoopClosureOptions::kSection);
}

void SlamOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const {
  slamOptionSchema().save(*this, target, section);
  loop_closure.saveToConfigFile(target, LoopClosureOptions::kSection);
}

void SlamOptions::dumpToTextStream(std::ostream& out) const {
  slamOptionSchema().dump(*this, out);
  loop_closure.dumpToTextStream(out);
}

void SlamOptions::validate(const std::string& file, const std::string& section) const {
  slamOptionSchema().validate(*this, file, section);
  if (kld.min_particles > particles)
    throw InputError(file, 0, "[" + section + "] min_particles",
                     "min_particles (" + std::to_string(kld.min_particles) + ") exceeds particles (" +
                         std::to_string(particles) + "), the adaptive set's maximum");
  loop_closure.validate(file);
}

}  // namespace gridtopo::slam
