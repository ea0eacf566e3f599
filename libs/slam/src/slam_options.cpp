#include "gridtopo/slam/slam_options.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"

namespace gridtopo::slam {

namespace {

// One table drives load, save and dump, so no key can be forgotten in one of them.
template <class F>
void forEachKey(SlamOptions& o, F&& f) {
  f("particles", o.particles);
  f("seed", o.seed);
  f("threads", o.threads);
  f("resample_threshold", o.resample_threshold);
  f("likelihood_gain", o.likelihood_gain);
  f("linear_update", o.linear_update);
  f("angular_update", o.angular_update);
  f("temporal_update", o.temporal_update);
  f("no_odometry_period", o.no_odometry_period);
  f("resolution", o.resolution);
  f("motion_alpha_rr", o.motion.alpha_rr);
  f("motion_alpha_rt", o.motion.alpha_rt);
  f("motion_alpha_tt", o.motion.alpha_tt);
  f("motion_alpha_tr", o.motion.alpha_tr);
  f("motion_min_sigma_xy", o.motion.min_sigma_xy);
  f("motion_min_sigma_theta", o.motion.min_sigma_theta);
  f("no_odometry_sigma_xy", o.motion.no_odometry_sigma_xy);
  f("no_odometry_sigma_theta", o.motion.no_odometry_sigma_theta);
  f("motion_scale_sigma", o.motion.scale_sigma);
  f("motion_scale_walk_sigma", o.motion.scale_walk_sigma);
  f("map_log_odds_hit", o.map.log_odds_hit);
  f("map_log_odds_free", o.map.log_odds_free);
  f("map_log_odds_min", o.map.log_odds_min);
  f("map_log_odds_max", o.map.log_odds_max);
  f("max_usable_range", o.beams.max_usable_range);
  f("min_range", o.beams.min_range);
  f("clear_no_return", o.beams.clear_no_return);
  f("no_return_range", o.beams.no_return_range);
  f("matching_beam_step", o.beams.matching_beam_step);
  f("matching_beam_angle", o.beams.matching_beam_angle);
  f("matching_range_margin", o.beams.matching_range_margin);
  f("matching_min_incidence", o.beams.matching_min_incidence);
  f("map_surface_clearance", o.beams.surface_clearance);
  f("match_sigma", o.matcher.sigma);
  f("match_kernel", o.matcher.kernel);
  f("match_null_log_likelihood", o.matcher.null_log_likelihood);
  f("match_occupied_log_odds", o.matcher.occupied_log_odds);
  f("match_free_check", o.matcher.free_check);
  f("match_use_motion_prior", o.matcher.use_motion_prior);
  f("match_gn_iterations", o.matcher.gn_iterations);
  f("match_gn_kernel", o.matcher.gn_kernel);
  f("match_polish_step_xy", o.matcher.polish_step_xy);
  f("match_polish_step_theta", o.matcher.polish_step_theta);
  f("match_polish_refinements", o.matcher.polish_refinements);
  f("match_step_xy", o.matcher.step_xy);
  f("match_step_theta", o.matcher.step_theta);
  f("match_refinements", o.matcher.refinements);
  f("match_coarse_levels", o.matcher.coarse_levels);
  f("match_coarse_beam_step", o.matcher.coarse_beam_step);
  f("match_max_iterations", o.matcher.max_iterations);
  f("match_min_fraction", o.matcher.min_match_fraction);
  f("proposal_points_per_axis", o.proposal.points_per_axis);
  f("proposal_delta_xy", o.proposal.delta_xy);
  f("proposal_delta_theta", o.proposal.delta_theta);
  f("proposal_min_sigma_xy", o.proposal.min_sigma_xy);
  f("proposal_min_sigma_theta", o.proposal.min_sigma_theta);
  f("proposal_laplace_weight", o.proposal.laplace_weight);
  f("proposal_start_spread", o.proposal.start_spread);
  f("proposal_report_mean", o.proposal.report_mean);
  f("proposal_beam_sigma", o.proposal.beam_sigma);
  f("proposal_min_curvature", o.proposal.min_curvature);
}

template <class E>
using Words = std::initializer_list<std::pair<const char*, E>>;

/// The proposal words: the INI key `proposal`, --proposal, toString and proposalFromString.
constexpr Words<ProposalType> kProposalWords{{"informed", ProposalType::Informed},
                                             {"mode-only", ProposalType::ModeOnly},
                                             {"hahnel", ProposalType::Hahnel},
                                             {"odometry", ProposalType::Odometry}};

// The keys whose value is one of a few words, with their words: one table for load, save and dump, in the order
// they are saved.
template <class F>
void forEachChoice(SlamOptions& o, F&& f) {
  f("proposal", o.proposal.type, kProposalWords);
  f("proposal_fit", o.proposal.fit,
    Words<ProposalFit>{{"quadratic", ProposalFit::Quadratic}, {"moments", ProposalFit::Moments}});
  f("proposal_weight", o.proposal.weight,
    Words<ProposalWeight>{{"mode", ProposalWeight::Mode}, {"integral", ProposalWeight::Integral}});
  f("match_method", o.matcher.method,
    Words<MatchMethod>{{"hill-climb", MatchMethod::HillClimb}, {"gauss-newton", MatchMethod::GaussNewton}});
  f("match_residual", o.matcher.residual,
    Words<MatchResidual>{{"point", MatchResidual::Point}, {"plane", MatchResidual::Plane}});
}

template <class E>
const char* wordOf(Words<E> words, E value) {
  for (const auto& [word, v] : words)
    if (v == value) return word;
  return "?";
}

template <class T>
std::string str(const T& v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

}  // namespace

const char* toString(ProposalType t) { return wordOf(kProposalWords, t); }

ProposalType proposalFromString(const std::string& s) {
  std::string all;
  for (const auto& [word, value] : kProposalWords) {
    if (s == word) return value;
    all += (all.empty() ? "" : ", ") + std::string(word);
  }
  throw std::invalid_argument("unknown proposal '" + s + "' (expected " + all + ")");
}

void SlamOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) {
  std::string file = "<ini>";
  // MRPT file-backed configs know their file name; memory ones do not.
  if (auto* f = dynamic_cast<const mrpt::config::CConfigFile*>(&source)) file = f->getAssociatedFile();
  forEachKey(*this, [&](const char* key, auto& value) {
    try {
      readIniValue(source, section, key, value);
    } catch (const InputError& e) {  // name the file too: "<file>: [section] key: cannot parse ..."
      throw InputError(file, 0, "[" + section + "] " + key, e.message());
    }
  });
  // Keys whose value is one of a few words: the word's enum value, or an error naming the words.
  forEachChoice(*this, [&](const char* key, auto& target, auto words) {
    if (!source.keyExists(section, key)) return;
    const std::string v = iniValueText(source.read_string(section, key, "", false));
    std::string expected;
    for (const auto& [word, value] : words) {
      if (v == word) {
        target = value;
        return;
      }
      expected += (expected.empty() ? "" : ", ") + std::string(word);
    }
    throw InputError(file, 0, "[" + section + "] " + key, "unknown value '" + v + "' (expected " + expected + ")");
  });
  validate(file, section);
}

void SlamOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const {
  auto& self = const_cast<SlamOptions&>(*this);
  forEachKey(self, [&](const char* key, auto& value) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, bool>) target.write(section, key, std::string(value ? "true" : "false"));
    else target.write(section, key, str(value));
  });
  forEachChoice(self, [&](const char* key, auto& value, auto words) {
    target.write(section, key, std::string(wordOf(words, value)));
  });
}

void SlamOptions::dumpToTextStream(std::ostream& out) const {
  out << "----------- [gridtopo::slam::SlamOptions] ------------\n";
  auto& self = const_cast<SlamOptions&>(*this);
  forEachKey(self, [&](const char* key, auto& value) {
    using T = std::decay_t<decltype(value)>;
    out << "  " << key << " = ";
    if constexpr (std::is_same_v<T, bool>) out << (value ? "true" : "false");
    else out << str(value);
    out << "\n";
  });
  forEachChoice(self, [&](const char* key, auto& value, auto words) {
    out << "  " << key << " = " << wordOf(words, value) << "\n";
  });
}

void SlamOptions::validate(const std::string& file, const std::string& section) const {
  auto fail = [&](const std::string& key, const std::string& msg) {
    throw InputError(file, 0, "[" + section + "] " + key, msg);
  };
  auto positive = [&](const char* key, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) fail(key, "must be a positive number, got " + str(v));
  };
  auto nonNegative = [&](const char* key, double v) {
    if (!(v >= 0.0) || !std::isfinite(v)) fail(key, "must be >= 0, got " + str(v));
  };
  if (particles < 1) fail("particles", "must be at least 1, got " + str(particles));
  if (particles > 100000) fail("particles", "must be at most 100000, got " + str(particles));
  if (threads < 0) fail("threads", "must be >= 0 (0 = all cores), got " + str(threads));
  if (!(resample_threshold >= 0.0 && resample_threshold <= 1.0))
    fail("resample_threshold", "must be in [0, 1], got " + str(resample_threshold));
  positive("likelihood_gain", likelihood_gain);
  positive("proposal_beam_sigma", proposal.beam_sigma);
  nonNegative("proposal_min_curvature", proposal.min_curvature);
  nonNegative("linear_update", linear_update);
  nonNegative("angular_update", angular_update);
  if (!std::isfinite(temporal_update)) fail("temporal_update", "must be finite");
  nonNegative("no_odometry_period", no_odometry_period);
  positive("resolution", resolution);
  if (resolution > 10.0) fail("resolution", "must be at most 10 m per cell, got " + str(resolution));
  nonNegative("motion_alpha_rr", motion.alpha_rr);
  nonNegative("motion_alpha_rt", motion.alpha_rt);
  nonNegative("motion_alpha_tt", motion.alpha_tt);
  nonNegative("motion_alpha_tr", motion.alpha_tr);
  positive("motion_min_sigma_xy", motion.min_sigma_xy);
  positive("motion_min_sigma_theta", motion.min_sigma_theta);
  positive("no_odometry_sigma_xy", motion.no_odometry_sigma_xy);
  positive("no_odometry_sigma_theta", motion.no_odometry_sigma_theta);
  if (!(motion.scale_sigma >= 0.0 && motion.scale_sigma <= 0.2))
    fail("motion_scale_sigma", "must be in [0, 0.2], got " + str(motion.scale_sigma));
  if (!(motion.scale_walk_sigma >= 0.0 && motion.scale_walk_sigma <= 0.2))
    fail("motion_scale_walk_sigma", "must be in [0, 0.2], got " + str(motion.scale_walk_sigma));
  if (!(map.log_odds_hit > 0.0f)) fail("map_log_odds_hit", "must be > 0, got " + str(map.log_odds_hit));
  if (!(map.log_odds_free < 0.0f)) fail("map_log_odds_free", "must be < 0, got " + str(map.log_odds_free));
  if (!(map.log_odds_min < 0.0f)) fail("map_log_odds_min", "must be < 0, got " + str(map.log_odds_min));
  if (!(map.log_odds_max > 0.0f)) fail("map_log_odds_max", "must be > 0, got " + str(map.log_odds_max));
  nonNegative("max_usable_range", beams.max_usable_range);
  nonNegative("min_range", beams.min_range);
  nonNegative("no_return_range", beams.no_return_range);
  if (beams.matching_beam_step < 0) fail("matching_beam_step", "must be >= 0, got " + str(beams.matching_beam_step));
  positive("matching_beam_angle", beams.matching_beam_angle);
  nonNegative("matching_range_margin", beams.matching_range_margin);
  nonNegative("map_surface_clearance", beams.surface_clearance);
  if (!(beams.matching_min_incidence >= 0.0 && beams.matching_min_incidence < 1.5))
    fail("matching_min_incidence", "must be in [0, 1.5) rad, got " + str(beams.matching_min_incidence));
  positive("match_sigma", matcher.sigma);
  if (matcher.kernel < 0 || matcher.kernel > 5) fail("match_kernel", "must be in [0, 5], got " + str(matcher.kernel));
  if (!(matcher.null_log_likelihood < 0.0))
    fail("match_null_log_likelihood", "must be < 0, got " + str(matcher.null_log_likelihood));
  if (!(matcher.occupied_log_odds >= map.log_odds_min && matcher.occupied_log_odds < map.log_odds_max))
    fail("match_occupied_log_odds", "must lie in [map_log_odds_min, map_log_odds_max)");
  positive("match_step_xy", matcher.step_xy);
  positive("match_step_theta", matcher.step_theta);
  if (matcher.refinements < 0) fail("match_refinements", "must be >= 0");
  if (matcher.coarse_levels < 0) fail("match_coarse_levels", "must be >= 0");
  if (matcher.coarse_beam_step < 1) fail("match_coarse_beam_step", "must be >= 1");
  if (matcher.max_iterations < 1) fail("match_max_iterations", "must be >= 1");
  if (matcher.gn_iterations < 0) fail("match_gn_iterations", "must be >= 0");
  if (matcher.gn_kernel < 0 || matcher.gn_kernel > 5) fail("match_gn_kernel", "must be in [0, 5]");
  positive("match_polish_step_xy", matcher.polish_step_xy);
  positive("match_polish_step_theta", matcher.polish_step_theta);
  if (matcher.polish_refinements < 0) fail("match_polish_refinements", "must be >= 0");
  if (!(matcher.min_match_fraction >= 0.0 && matcher.min_match_fraction <= 1.0))
    fail("match_min_fraction", "must be in [0, 1], got " + str(matcher.min_match_fraction));
  if (proposal.points_per_axis < 2 || proposal.points_per_axis > 9)
    fail("proposal_points_per_axis", "must be in [2, 9], got " + str(proposal.points_per_axis));
  positive("proposal_delta_xy", proposal.delta_xy);
  positive("proposal_delta_theta", proposal.delta_theta);
  nonNegative("proposal_min_sigma_xy", proposal.min_sigma_xy);
  nonNegative("proposal_min_sigma_theta", proposal.min_sigma_theta);
  nonNegative("proposal_start_spread", proposal.start_spread);
}

}  // namespace gridtopo::slam
