#include "gridtopo/io/log_import_args.h"

namespace gridtopo::io {

LogImportArgs::LogImportArgs(TCLAP::CmdLine& cmd)
    : layout_("l", "layout",
              "rawlog layout: 'sf' (CActionCollection + CSensoryFrame pairs, default) or 'obs' (CObservationOdometry + "
              "CObservation2DRangeScan)",
              false, "sf", "sf|obs", cmd),
      odometry_("", "odometry",
                "CARMEN odometry source: 'laser' (pose inside each laser line, default) or 'odom' (ODOM lines "
                "interpolated at the scan time)",
                false, "laser", "laser|odom", cmd),
      motion_model_("", "motion-model",
                    "motion model of the actions (sf layout): 'gaussian' (default) or 'thrun' (MRPT's defaults)", false,
                    "gaussian", "gaussian|thrun", cmd),
      compression_("", "compression", "gzip level 0-9 of the output (default: 1 if the name ends in .gz, else 0 = plain)",
                   false, -1, "level", cmd),
      gz_("", "gz", "gzip-compress the output (level 1, like MRPT's tools)", cmd),
      sensor_label_("", "sensor-label", "sensorLabel of the scans (default LASER)", false, "LASER", "label", cmd),
      max_range_("", "max-range", "CARMEN: laser max range (m) when no PARAM gives it (default 50)", false, 50.0,
                 "metres", cmd),
      skip_bad_lines_("", "skip-bad-lines",
                      "CARMEN: skip malformed lines (counted and reported) instead of stopping at the first one", cmd),
      rear_laser_("", "rear-laser", "CARMEN: also import RLASER (rear laser) scans", cmd) {}

LogImportOptions LogImportArgs::options() const {
  // TCLAP's getValue is not const.
  auto& self = const_cast<LogImportArgs&>(*this);
  LogImportOptions o;
  o.layout = self.layout_.getValue();
  o.odometry = self.odometry_.getValue();
  o.motion_model = self.motion_model_.getValue();
  o.compression = self.compression_.getValue();
  o.gz = self.gz_.getValue();
  o.sensor_label = self.sensor_label_.getValue();
  o.max_range = self.max_range_.getValue();
  o.skip_bad_lines = self.skip_bad_lines_.getValue();
  o.rear_laser = self.rear_laser_.getValue();
  return o;
}

}  // namespace gridtopo::io
