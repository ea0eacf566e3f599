#include "gridtopo/io/rawlog_io.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>
#include <zlib.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "isolated_parse.h"
#include "rawlog_entry.h"

namespace gridtopo::io {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Keeps phi bit-exact (the CPose2D constructor wraps it through +/- pi arithmetic).
mrpt::poses::CPose2D toCPose(const mrpt::math::TPose2D& p) {
  mrpt::poses::CPose2D c(p.x, p.y, 0.0);
  c.phi(p.phi);
  return c;
}
mrpt::math::TPose2D toTPose(const mrpt::poses::CPose2D& p) { return {p.x(), p.y(), p.phi()}; }

// Linear interpolation of two poses (shortest way round for the angle); f in [0, 1].
mrpt::math::TPose2D interpolate(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b, double f) {
  const double dphi = mrpt::math::wrapToPi(b.phi - a.phi);
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), mrpt::math::wrapToPi(a.phi + f * dphi)};
}

// A gzip file cut inside its last block or trailer can still decompress to complete objects: check that the
// gzip stream itself is whole (one extra decompression pass, ~50 ms for Intel).
void checkGzipIntegrity(const std::string& path) {
  std::ifstream raw(path, std::ios::binary);
  unsigned char magic[2] = {0, 0};
  raw.read(reinterpret_cast<char*>(magic), 2);
  if (raw.gcount() < 2 || magic[0] != 0x1f || magic[1] != 0x8b) return;
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw InputError(path, "cannot open rawlog file");
  std::vector<char> buf(1 << 20);
  int got = 0;
  while ((got = gzread(f, buf.data(), static_cast<unsigned>(buf.size()))) > 0) {
  }
  int err = Z_OK;
  const char* msg = gzerror(f, &err);
  gzclose(f);
  if (got < 0 || (err != Z_OK && err != Z_STREAM_END))
    throw InputError(path, 0, "gzip", std::string("corrupt or truncated gzip data: ") + (msg ? msg : "?"));
}

}  // namespace

RawlogLayout parseRawlogLayout(const std::string& name) {
  if (name == "sf" || name == "action-sf" || name == "action") return RawlogLayout::ActionSensoryFrame;
  if (name == "obs" || name == "observations" || name == "observation-only") return RawlogLayout::ObservationOnly;
  throw std::invalid_argument("unknown rawlog layout '" + name + "' (expected 'sf' or 'obs')");
}

const char* rawlogLayoutName(RawlogLayout layout) { return layout == RawlogLayout::ActionSensoryFrame ? "sf" : "obs"; }

RawlogWriteStats writeRawlog(const std::string& path, const std::vector<ScanRecord>& records,
                             const RawlogWriteOptions& options) {
  const int level = options.compression_level >= 0 ? options.compression_level : (endsWith(path, ".gz") ? 1 : 0);
  if (level > 9) throw std::invalid_argument("gzip compression level must be 0..9");

  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motion;
  motion.modelSelection = options.motion_model == MotionModel::Thrun ? mrpt::obs::CActionRobotMovement2D::mmThrun
                                                                     : mrpt::obs::CActionRobotMovement2D::mmGaussian;

  // Convert everything first: a record MRPT cannot hold fails before any file is created.
  std::vector<mrpt::obs::CObservation2DRangeScan::Ptr> scans;
  scans.reserve(records.size());
  for (std::size_t i = 0; i < records.size(); ++i) {
    try {
      scans.push_back(toMrptScan(records[i].scan, options.scan));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("scan " + std::to_string(i) + " (source line/entry " +
                                  std::to_string(records[i].source_index) + "): " + e.what());
    }
  }

  RawlogWriteStats stats;
  writeFileAtomically(path, [&](const std::string& tmp) {
    std::unique_ptr<mrpt::io::CStream> out;
    if (level > 0) {
      auto gz = std::make_unique<mrpt::io::CFileGZOutputStream>();
      if (!gz->open(tmp, level)) throw std::runtime_error("cannot open " + tmp + " for writing");
      out = std::move(gz);
    } else {
      auto f = std::make_unique<mrpt::io::CFileOutputStream>();
      if (!f->open(tmp)) throw std::runtime_error("cannot open " + tmp + " for writing");
      out = std::move(f);
    }
    auto arch = mrpt::serialization::archiveFrom(*out);
    std::optional<mrpt::poses::CPose2D> last_odometry;
    for (std::size_t i = 0; i < records.size(); ++i) {
      const ScanRecord& rec = records[i];
      const auto& scan = scans[i];
      if (options.layout == RawlogLayout::ActionSensoryFrame) {
        mrpt::obs::CActionCollection acts;
        if (rec.has_odometry) {
          const mrpt::poses::CPose2D odo = toCPose(rec.odometry);
          const mrpt::poses::CPose2D increment = last_odometry ? odo - *last_odometry : mrpt::poses::CPose2D();
          mrpt::obs::CActionRobotMovement2D move;
          move.computeFromOdometry(increment, motion);
          move.timestamp = scan->timestamp;
          acts.insert(move);
          last_odometry = odo;
        }
        mrpt::obs::CSensoryFrame sf;
        sf.insert(scan);
        arch << acts << sf;
        stats.entries += 2;
      } else {
        if (rec.has_odometry) {
          mrpt::obs::CObservationOdometry odo;
          odo.sensorLabel = options.odometry_label;
          odo.timestamp = scan->timestamp;
          odo.odometry = toCPose(rec.odometry);
          arch << odo;
          ++stats.entries;
        }
        arch << *scan;
        ++stats.entries;
      }
      if (rec.has_odometry) ++stats.with_odometry;
      ++stats.scans;
      if (options.progress) options.progress(i + 1);
    }
    out.reset();  // flush and close before the rename
  });
  return stats;
}

RawlogWriteStats writeRawlog(const std::string& path, const std::vector<ScanRecord>& records) {
  static const RawlogWriteOptions defaults;
  return writeRawlog(path, records, defaults);
}

namespace {

/// Parses the rawlog in this process. `entry_reached`, when given, is set to the index of each top-level entry
/// before it is read (so that a crash can be located).
RawlogContents parseRawlog(const std::string& path, volatile std::uint64_t* entry_reached) {
  namespace obs = mrpt::obs;
  RawlogContents out;
  out.path = path;
  mrpt::io::CFileGZInputStream in;
  if (!in.open(path)) throw InputError(path, "cannot open rawlog file");
  auto arch = mrpt::serialization::archiveFrom(in);

  // Odometry sources gathered while streaming; resolved per scan at the end.
  struct OdoObs {
    double t;
    mrpt::math::TPose2D pose;
  };
  std::vector<OdoObs> odometry_obs;
  std::vector<std::size_t> odo_before;                          // per scan: number of odometry observations before it
  std::vector<std::optional<mrpt::math::TPose2D>> action_pose;  // per scan: accumulated action odometry
  mrpt::poses::CPose2D accumulated;
  bool any_movement = false, last_collection_moved = false;

  auto addScan = [&](const obs::CObservation2DRangeScan& o, std::size_t entry) {
    ScanRecord rec;
    try {
      rec.scan = fromMrptScan(o);
    } catch (const std::exception& e) {
      throw InputError(path, 0, "entry " + std::to_string(entry), e.what());
    }
    rec.source_index = entry;
    out.scans.push_back(std::move(rec));
    odo_before.push_back(odometry_obs.size());
    action_pose.push_back(last_collection_moved ? std::optional(toTPose(accumulated)) : std::nullopt);
  };
  auto addOdometry = [&](const obs::CObservationOdometry& o) {
    odometry_obs.push_back({fromMrptTime(o.timestamp), toTPose(o.odometry)});
    ++out.odometry_observations;
  };

  for (std::size_t entry = 0;; ++entry) {
    mrpt::serialization::CSerializable::Ptr object;
    const uint64_t position = in.getPosition();
    if (entry_reached) *entry_reached = entry;
    try {
      object = arch.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      if (in.getPosition() != position)
        throw InputError(path, 0, "entry " + std::to_string(entry), "file truncated inside an object");
      break;
    } catch (const std::exception& e) {
      std::string msg = e.what();
      msg = innermostMrptMessage(msg);
      throw InputError(path, 0, "entry " + std::to_string(entry),
                       "cannot read an MRPT object (corrupt, truncated or not a rawlog): " + msg);
    }
    ++out.entries;
    if (!object) continue;
    if (auto acts = std::dynamic_pointer_cast<obs::CActionCollection>(object)) {
      ++out.actions;
      out.has_actions = true;
      last_collection_moved = false;
      if (auto move = acts->getBestMovementEstimation()) {
        const mrpt::poses::CPose2D inc = move->estimationMethod == obs::CActionRobotMovement2D::emOdometry
                                             ? move->rawOdometryIncrementReading
                                             : move->poseChange->getMeanVal();
        accumulated = accumulated + inc;
        any_movement = last_collection_moved = true;
      }
    } else if (auto sf = std::dynamic_pointer_cast<obs::CSensoryFrame>(object)) {
      ++out.sensory_frames;
      for (const auto& o : *sf) {
        if (auto scan = std::dynamic_pointer_cast<obs::CObservation2DRangeScan>(o))
          addScan(*scan, entry);
        else if (auto odo = std::dynamic_pointer_cast<obs::CObservationOdometry>(o))
          addOdometry(*odo);
      }
    } else if (auto scan = std::dynamic_pointer_cast<obs::CObservation2DRangeScan>(object)) {
      ++out.observations;
      addScan(*scan, entry);
    } else if (auto odo = std::dynamic_pointer_cast<obs::CObservationOdometry>(object)) {
      ++out.observations;
      addOdometry(*odo);
    } else {
      if (std::dynamic_pointer_cast<obs::CObservation>(object)) ++out.observations;
      ++out.skipped_objects;
    }
  }

  for (std::size_t i = 0; i < out.scans.size(); ++i) {
    ScanRecord& rec = out.scans[i];
    if (any_movement) {
      rec.has_odometry = action_pose[i].has_value();
      if (rec.has_odometry) rec.odometry = *action_pose[i];
      continue;
    }
    const std::size_t j = odo_before[i];
    const double t = rec.scan.timestamp;
    if (j > 0) {
      const OdoObs& prev = odometry_obs[j - 1];
      rec.has_odometry = true;
      rec.odometry = prev.pose;
      if (j < odometry_obs.size()) {
        const OdoObs& next = odometry_obs[j];
        if (next.t > prev.t && prev.t < t && t <= next.t)
          rec.odometry = interpolate(prev.pose, next.pose, (t - prev.t) / (next.t - prev.t));
      }
    } else if (!odometry_obs.empty()) {
      rec.has_odometry = true;
      rec.odometry = odometry_obs.front().pose;
    }
  }
  return out;
}

}  // namespace

RawlogContents readRawlog(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "no such rawlog file");
  checkGzipIntegrity(path);
  // MRPT 2.5.8's deserialiser can crash (segmentation fault) on corrupted -- not truncated -- data, e.g. inside
  // CActionRobotMovement2D::serializeFrom, or allocate gigabytes for a corrupted size field: parse in a child
  // process first (isolated_parse.h).
  checkParsesInChild(path, [&](volatile std::uint64_t* entry) { parseRawlog(path, entry); });
  return parseRawlog(path, nullptr);
}

}  // namespace gridtopo::io

// The rawlog reader for libgridtopo_io_core's readScanLog, which loads this library only for a rawlog.
extern "C" void gridtopo_io_read_rawlog_scans(const std::string& path, gridtopo::io::RawlogScans& out) {
  gridtopo::io::RawlogContents raw = gridtopo::io::readRawlog(path);
  out.entries = raw.entries;
  out.odometry_observations = raw.odometry_observations;
  out.has_actions = raw.has_actions;
  out.scans = std::move(raw.scans);
}
