#pragma once
// Every tunable of the RBPF SLAM with its default, loadable from an INI section (MRPT TLoadableOptions style).
// One key table (slamOptionSchema: key, member, range, unit, help) gives load, save, dump, validation, the key list
// of the strict RUN.ini checks, `gridtopo-slam --help-options` and the GUI's property grid. config-ini/slam.ini
// documents each key at length (a test keeps its keys equal to the table's).
#include <mrpt/config/CLoadableOptions.h>

#include <cstdint>
#include <string>

#include "gridtopo/core/option_schema.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/kld_sampling.h"
#include "gridtopo/slam/loop_closure_options.h"
#include "gridtopo/slam/motion_model.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/scan_matcher.h"

namespace gridtopo::slam {

struct SlamOptions : public mrpt::config::CLoadableOptions {
  // Filter
  int particles = 30;
  std::uint64_t seed = 1;
  int threads = 0;                  ///< 0 = all cores
  double resample_threshold = 0.5;  ///< resample when N_eff < threshold · N
  /// The adaptive particle set (KLD-sampling at each resampling; off while kld.min_particles = 0): `particles` is
  /// then the maximum.
  KldOptions kld;
  /// The observation log-likelihood is divided by this before it enters τ_j and the weights (GMapping's
  /// softening of the over-confident independent-beam model).
  double likelihood_gain = 10.0;

  // Update policy (GMapping's linearUpdate / angularUpdate / temporalUpdate)
  double linear_update = 0.25;    ///< m of travelled distance since the last processed scan
  double angular_update = 0.15;   ///< rad of accumulated rotation
  double temporal_update = -1.0;  ///< s since the last processed scan; < 0 disables
  /// Logs without odometry: process a scan when this many seconds passed (0 = every scan).
  double no_odometry_period = 0.0;

  double resolution = 0.05;  ///< m per cell

  MotionModelOptions motion;
  MapUpdateOptions map;
  BeamOptions beams;
  ScanMatcherOptions matcher;
  ProposalOptions proposal;
  /// The pose graph over the filter, in its own section [loop_closure] (loopClosureOptionSchema): the
  /// section-taking methods below read and write it beside the filter's section.
  LoopClosureOptions loop_closure;

  /// Loads `section` and [loop_closure] (each key that is present); throws gridtopo::InputError(file, 0, "[section] key", reason) on invalid values.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  void dumpToTextStream(std::ostream& out) const override;
  /// Throws gridtopo::InputError(file, 0, "[section] key", ...) when a value is out of its range.
  void validate(const std::string& file = "<options>", const std::string& section = "slam") const;
};

/// The key table of [slam] (the defaults are a default-constructed SlamOptions').
const OptionSchema<SlamOptions>& slamOptionSchema();

const char* toString(ProposalType t);
/// "informed" / "mode-only" / "odometry"; throws std::invalid_argument otherwise.
ProposalType proposalFromString(const std::string& s);

}  // namespace gridtopo::slam
