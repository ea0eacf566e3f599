#pragma once
// gridtopo-import's reader and writer flags (--layout, --odometry, --motion-model, --compression, --gz,
// --sensor-label, --max-range, --skip-bad-lines, --rear-laser) on a TCLAP command line, and their values as
// LogImportOptions.
#include <tclap/CmdLine.h>

#include <string>

#include "gridtopo/io/log_import.h"

namespace gridtopo::io {

class LogImportArgs {
 public:
  /// Adds the flags to `cmd`, in the order above.
  explicit LogImportArgs(TCLAP::CmdLine& cmd);
  /// The parsed values (after cmd.parse).
  LogImportOptions options() const;

 private:
  TCLAP::ValueArg<std::string> layout_, odometry_, motion_model_;
  TCLAP::ValueArg<int> compression_;
  TCLAP::SwitchArg gz_;
  TCLAP::ValueArg<std::string> sensor_label_;
  TCLAP::ValueArg<double> max_range_;
  TCLAP::SwitchArg skip_bad_lines_, rear_laser_;
};

}  // namespace gridtopo::io
