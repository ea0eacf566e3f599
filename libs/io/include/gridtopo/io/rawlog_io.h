#pragma once
// MRPT rawlogs in and out, in both of MRPT's layouts:
//  - action / sensory frame: per scan a CActionCollection holding a CActionRobotMovement2D (the odometry
//    increment since the previous scan, with MRPT's motion model) followed by a CSensoryFrame with the scan.
//    This is what MRPT's rbpf-slam / icp-slam consume. It carries only relative odometry: read back, the
//    odometry starts at (0, 0, 0) at the first scan.
//  - observation-only: per scan a CObservationOdometry (absolute odometry pose) followed by a
//    CObservation2DRangeScan, both with the scan's timestamp.
// Rawlogs may be gzip-compressed (MRPT reads both transparently).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

enum class RawlogLayout {
  ActionSensoryFrame,  ///< CActionCollection + CSensoryFrame pairs ("sf")
  ObservationOnly,     ///< a flat sequence of CObservation objects ("obs")
};

/// "sf" / "obs" (also accepts "action-sf", "observations"); throws std::invalid_argument otherwise.
RawlogLayout parseRawlogLayout(const std::string& name);
const char* rawlogLayoutName(RawlogLayout layout);

enum class MotionModel {
  Gaussian,  ///< CActionRobotMovement2D::mmGaussian (closed form, small files; default)
  Thrun,     ///< CActionRobotMovement2D::mmThrun (particles; MRPT draws them when it loads the action)
};

struct RawlogWriteOptions {
  RawlogLayout layout = RawlogLayout::ActionSensoryFrame;
  MotionModel motion_model = MotionModel::Gaussian;  ///< other motion-model parameters: MRPT's defaults
  /// gzip level 0-9; -1 = gzip (level 1, like MRPT's tools) if the path ends in ".gz", else plain.
  int compression_level = -1;
  ScanConversionOptions scan;
  std::string odometry_label = "ODOMETRY";  ///< sensorLabel of CObservationOdometry (observation-only layout)
  std::function<void(std::size_t scans_done)> progress;  ///< called after each scan written (optional)
};

struct RawlogWriteStats {
  std::size_t scans = 0;
  std::size_t entries = 0;        ///< objects written
  std::size_t with_odometry = 0;  ///< scans that carried odometry
};

/// Writes the records as an MRPT rawlog, atomically (temporary file + rename). A record without odometry gets
/// an empty CActionCollection (sf) or no CObservationOdometry (obs); the next increment starts from the last
/// odometry seen. The first scan's increment is zero. Throws std::invalid_argument on a record MRPT cannot
/// hold (see toMrptScan) and std::runtime_error on I/O errors.
RawlogWriteStats writeRawlog(const std::string& path, const std::vector<ScanRecord>& records,
                             const RawlogWriteOptions& options);
/// The same with default options (action / sensory-frame layout, Gaussian motion model).
RawlogWriteStats writeRawlog(const std::string& path, const std::vector<ScanRecord>& records);

struct RawlogContents {
  std::string path;
  std::vector<ScanRecord> scans;   ///< every CObservation2DRangeScan, in file order
  std::size_t entries = 0;         ///< top-level objects in the file
  std::size_t actions = 0;         ///< CActionCollection entries
  std::size_t sensory_frames = 0;  ///< CSensoryFrame entries
  std::size_t observations = 0;    ///< top-level CObservation entries
  std::size_t odometry_observations = 0;
  std::size_t skipped_objects = 0;  ///< objects of other classes (images, IMU, ...) ignored
  bool has_actions = false;         ///< true: action / sensory-frame layout (or mixed)
};

/// Reads an MRPT rawlog (either layout, plain or gzip), streaming. Odometry of each scan: action layout -> the
/// accumulated CActionRobotMovement2D increments (starting at 0,0,0); observation-only layout -> the latest
/// CObservationOdometry before the scan in the file, linearly interpolated at the scan's timestamp when the
/// next one brackets it (the next one alone if there is none before). No odometry in the file ->
/// has_odometry = false. source_index = 0-based index of the top-level entry holding the scan.
/// Throws gridtopo::InputError (file, "entry N") on unreadable or truncated files.
RawlogContents readRawlog(const std::string& path);

}  // namespace gridtopo::io
