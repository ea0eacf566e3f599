#include "gridtopo/io/log_import.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"

namespace gridtopo::io {

LogReadOptions logReadOptions(const LogImportOptions& o) {
  LogReadOptions r;
  r.carmen.skip_bad_lines = o.skip_bad_lines;
  r.carmen.read_rear_laser = o.rear_laser;
  if (!(o.max_range > 0.0) || !std::isfinite(o.max_range))
    throw std::invalid_argument("--max-range must be a positive number of metres");
  r.carmen.default_max_range = o.max_range;
  if (o.odometry == "laser")
    r.odometry = OdometrySource::LaserLines;
  else if (o.odometry == "odom")
    r.odometry = OdometrySource::OdomLines;
  else
    throw std::invalid_argument("--odometry must be 'laser' or 'odom', not '" + o.odometry + "'");
  return r;
}

RawlogWriteOptions rawlogWriteOptions(const LogImportOptions& o) {
  RawlogWriteOptions w;
  w.layout = parseRawlogLayout(o.layout);
  if (o.motion_model == "gaussian")
    w.motion_model = MotionModel::Gaussian;
  else if (o.motion_model == "thrun")
    w.motion_model = MotionModel::Thrun;
  else
    throw std::invalid_argument("--motion-model must be 'gaussian' or 'thrun'");
  w.compression_level = o.compression;
  if (w.compression_level > 9 || w.compression_level < -1) throw std::invalid_argument("--compression must be 0..9");
  if (o.gz && w.compression_level < 0) w.compression_level = 1;
  w.scan.sensor_label = o.sensor_label;
  return w;
}

std::string stageRawlog(OutputSet& outputs, const std::string& path, const std::vector<ScanRecord>& scans,
                        RawlogWriteOptions options, bool quiet, const std::string& input) {
  if (scans.empty()) throw InputError(input, "the log holds no laser scans: nothing to write");
  ProgressBar bar(scans.size(), "writing", "scans", quiet ? 0 : -1);
  options.progress = [&](std::size_t done) { bar.update(done); };
  RawlogWriteStats stats;
  outputs.write(path, [&](const std::string& tmp) { stats = writeRawlog(tmp, scans, options); });
  bar.finish();
  std::ostringstream o;
  o << "output:             " << path << " (" << rawlogLayoutName(options.layout) << " layout, " << stats.entries
    << " entries, " << stats.scans << " scans, " << stats.with_odometry << " with odometry)\n";
  return o.str();
}

}  // namespace gridtopo::io
