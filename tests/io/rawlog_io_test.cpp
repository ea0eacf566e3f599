#include "gridtopo/io/rawlog_io.h"

#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/poses/CPosePDFParticles.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "gridtopo/core/error.h"
#include "synthetic_scans.h"
#include "test_tmp_dir.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::io;

using gridtopo::test::tmpDir;

namespace {
double maxEndpointError(const LaserScan& a, const LaserScan& b) {
  double worst = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const auto pa = beamEndpointInRobotFrame(a, k), pb = beamEndpointInRobotFrame(b, k);
    worst = std::max(worst, std::hypot(pa.x - pb.x, pa.y - pb.y));
  }
  return worst;
}

std::string readBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}
}  // namespace

TEST(Rawlog, ObservationLayoutRoundTripsScansOdometryAndTimestamps) {
  const auto in = gridtopo::test::syntheticRecords();
  for (const bool gz : {false, true}) {
    SCOPED_TRACE(gz);
    const fs::path p = tmpDir() / (gz ? "obs.rawlog.gz" : "obs.rawlog");
    RawlogWriteOptions opt;
    opt.layout = RawlogLayout::ObservationOnly;
    const auto stats = writeRawlog(p.string(), in, opt);
    EXPECT_EQ(stats.scans, 40u);
    EXPECT_EQ(stats.entries, 80u);
    const std::string bytes = readBytes(p);
    ASSERT_GE(bytes.size(), 2u);
    EXPECT_EQ(static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b, gz);

    const RawlogContents c = readRawlog(p.string());
    EXPECT_FALSE(c.has_actions);
    EXPECT_EQ(c.entries, 80u);
    EXPECT_EQ(c.odometry_observations, 40u);
    ASSERT_EQ(c.scans.size(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      const auto& a = in[i];
      const auto& b = c.scans[i];
      EXPECT_EQ(b.scan.timestamp, a.scan.timestamp);  // microsecond timestamps survive exactly
      EXPECT_LT(maxEndpointError(a.scan, b.scan), 1e-9);
      EXPECT_EQ(b.scan.valid, a.scan.valid);
      ASSERT_TRUE(b.has_odometry);
      EXPECT_EQ(b.odometry.x, a.odometry.x);  // absolute odometry, exact
      EXPECT_EQ(b.odometry.y, a.odometry.y);
      EXPECT_EQ(b.odometry.phi, a.odometry.phi);
      EXPECT_EQ(b.source_index, 2 * i + 1);
    }
    // Timestamps stepping backwards are kept in file order.
    EXPECT_LT(c.scans[7].scan.timestamp, c.scans[6].scan.timestamp);
  }
}

TEST(Rawlog, ActionLayoutKeepsRelativeOdometryStartingAtTheOrigin) {
  const auto in = gridtopo::test::syntheticRecords();
  const fs::path p = tmpDir() / "sf.rawlog";
  writeRawlog(p.string(), in);
  const RawlogContents c = readRawlog(p.string());
  EXPECT_TRUE(c.has_actions);
  EXPECT_EQ(c.actions, 40u);
  EXPECT_EQ(c.sensory_frames, 40u);
  ASSERT_EQ(c.scans.size(), 40u);
  const mrpt::poses::CPose2D p0(in[0].odometry.x, in[0].odometry.y, in[0].odometry.phi);
  for (std::size_t i = 0; i < in.size(); ++i) {
    const mrpt::poses::CPose2D pi(in[i].odometry.x, in[i].odometry.y, in[i].odometry.phi);
    const mrpt::poses::CPose2D expected = pi - p0;  // the pose in the frame of the first one
    const auto& o = c.scans[i].odometry;
    ASSERT_TRUE(c.scans[i].has_odometry);
    EXPECT_NEAR(o.x, expected.x(), 1e-9);
    EXPECT_NEAR(o.y, expected.y(), 1e-9);
    EXPECT_NEAR(mrpt::math::wrapToPi(o.phi - expected.phi()), 0.0, 1e-9);
    EXPECT_EQ(c.scans[i].scan.timestamp, in[i].scan.timestamp);
    EXPECT_LT(maxEndpointError(in[i].scan, c.scans[i].scan), 1e-9);
  }
  EXPECT_EQ(c.scans[0].odometry.x, 0.0);
}

TEST(Rawlog, MrptsOwnLoaderAcceptsBothLayouts) {
  const auto in = gridtopo::test::syntheticRecords();
  const fs::path sf = tmpDir() / "mrpt_sf.rawlog", ob = tmpDir() / "mrpt_obs.rawlog.gz";
  writeRawlog(sf.string(), in);
  RawlogWriteOptions opt;
  opt.layout = RawlogLayout::ObservationOnly;
  writeRawlog(ob.string(), in, opt);

  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(sf.string()));
  ASSERT_EQ(raw.size(), 80u);
  for (std::size_t i = 0; i < raw.size(); ++i)
    EXPECT_EQ(raw.getType(i), i % 2 ? mrpt::obs::CRawlog::etSensoryFrame : mrpt::obs::CRawlog::etActionCollection);
  // The second action: the odometry increment between scans 0 and 1, as a Gaussian with MRPT's default model.
  const auto acts = raw.getAsAction(2);
  const auto move = acts->getBestMovementEstimation();
  ASSERT_TRUE(move);
  const mrpt::poses::CPose2D p0(in[0].odometry.x, in[0].odometry.y, in[0].odometry.phi);
  const mrpt::poses::CPose2D p1(in[1].odometry.x, in[1].odometry.y, in[1].odometry.phi);
  const mrpt::poses::CPose2D inc = p1 - p0;
  EXPECT_NEAR(move->poseChange->getMeanVal().x(), inc.x(), 1e-12);
  EXPECT_NEAR(move->poseChange->getMeanVal().phi(), inc.phi(), 1e-12);
  EXPECT_TRUE(IS_CLASS(*move->poseChange, mrpt::poses::CPosePDFGaussian));
  const auto sf1 = raw.getAsObservations(3);
  const auto scan = sf1->getObservationByClass<mrpt::obs::CObservation2DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_EQ(scan->getScanSize(), 180u);
  // Scan 1 is interleaved: -89.5 .. +89.5 deg, i.e. symmetric: centre yaw 0 + mounting yaw 0.
  EXPECT_NEAR(scan->sensorPose.yaw(), 0.0, 1e-15);
  EXPECT_FLOAT_EQ(scan->aperture, static_cast<float>(179.0 * M_PI / 180.0));
  EXPECT_NEAR(scan->sensorPose.x(), 0.12, 1e-15);
  EXPECT_NEAR(scan->sensorPose.y(), -0.03, 1e-15);
  EXPECT_EQ(mrpt::Clock::toDouble(scan->timestamp), 1002560357.418569);

  mrpt::obs::CRawlog raw2;
  ASSERT_TRUE(raw2.loadFromRawLogFile(ob.string()));
  ASSERT_EQ(raw2.size(), 80u);
  EXPECT_EQ(raw2.getType(0), mrpt::obs::CRawlog::etObservation);
  const auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(raw2.getAsObservation(2));
  ASSERT_TRUE(odo);
  EXPECT_EQ(odo->odometry.x(), in[1].odometry.x);
  const auto scan0 = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(raw2.getAsObservation(1));
  ASSERT_TRUE(scan0);
  EXPECT_NEAR(scan0->sensorPose.yaw(), -0.5 * M_PI / 180.0, 1e-15);
}

TEST(Rawlog, LogWithoutOdometryReadsBackWithoutOdometry) {
  auto in = gridtopo::test::syntheticRecords({5});
  for (auto& r : in) r.has_odometry = false;
  for (const auto layout : {RawlogLayout::ActionSensoryFrame, RawlogLayout::ObservationOnly}) {
    const fs::path p = tmpDir() / "noodo.rawlog";
    RawlogWriteOptions opt;
    opt.layout = layout;
    const auto stats = writeRawlog(p.string(), in, opt);
    EXPECT_EQ(stats.with_odometry, 0u);
    const auto c = readRawlog(p.string());
    ASSERT_EQ(c.scans.size(), 5u);
    for (const auto& r : c.scans) EXPECT_FALSE(r.has_odometry);
  }
}

TEST(Rawlog, ObservationOdometryIsInterpolatedAtTheScanTime) {
  // Hand-made observation-only rawlog: odometry at t = 10 and t = 11, a scan at t = 10.25 between them,
  // one before any odometry (gets the first one) and one after the last (gets the last one).
  const fs::path p = tmpDir() / "interp.rawlog";
  {
    mrpt::io::CFileGZOutputStream f(p.string());
    auto arch = mrpt::serialization::archiveFrom(f);
    auto scanAt = [](double t) {
      LaserScan s;
      s.timestamp = t;
      s.angle_increment = M_PI / 180;
      s.start_angle = -M_PI / 2;
      s.max_range = 10;
      s.ranges.assign(181, 1.0f);
      s.valid.assign(181, 1);
      return toMrptScan(s);
    };
    auto odoAt = [](double t, double x, double phi) {
      mrpt::obs::CObservationOdometry o;
      o.timestamp = toMrptTime(t);
      o.odometry = mrpt::poses::CPose2D(x, 2 * x, phi);
      return o;
    };
    arch << *scanAt(9.5) << odoAt(10.0, 1.0, 3.0) << *scanAt(10.25) << odoAt(11.0, 3.0, -3.0) << *scanAt(11.5);
  }
  const auto c = readRawlog(p.string());
  ASSERT_EQ(c.scans.size(), 3u);
  EXPECT_EQ(c.odometry_observations, 2u);
  ASSERT_TRUE(c.scans[0].has_odometry);
  EXPECT_EQ(c.scans[0].odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(c.scans[1].odometry.x, 1.5);
  EXPECT_DOUBLE_EQ(c.scans[1].odometry.y, 3.0);
  // 3 rad -> -3 rad the short way (through pi): a quarter of 2*pi - 6.
  EXPECT_NEAR(c.scans[1].odometry.phi, 3.0 + 0.25 * (2 * M_PI - 6.0), 1e-12);
  EXPECT_EQ(c.scans[2].odometry.x, 3.0);
}

TEST(Rawlog, ThrunModelIsStoredAndDeterministic) {
  const auto in = gridtopo::test::syntheticRecords({6});
  RawlogWriteOptions opt;
  opt.motion_model = MotionModel::Thrun;
  const fs::path a = tmpDir() / "thrun_a.rawlog", b = tmpDir() / "thrun_b.rawlog";
  writeRawlog(a.string(), in, opt);
  writeRawlog(b.string(), in, opt);
  EXPECT_EQ(readBytes(a), readBytes(b));
  mrpt::obs::CRawlog raw;
  ASSERT_TRUE(raw.loadFromRawLogFile(a.string()));
  const auto move = raw.getAsAction(2)->getBestMovementEstimation();
  ASSERT_TRUE(move);
  EXPECT_EQ(move->motionModelConfiguration.modelSelection, mrpt::obs::CActionRobotMovement2D::mmThrun);
  EXPECT_TRUE(IS_CLASS(*move->poseChange, mrpt::poses::CPosePDFParticles));
  const auto c = readRawlog(a.string());
  ASSERT_EQ(c.scans.size(), 6u);
  const mrpt::poses::CPose2D p0(in[0].odometry.x, in[0].odometry.y, in[0].odometry.phi);
  const mrpt::poses::CPose2D p5(in[5].odometry.x, in[5].odometry.y, in[5].odometry.phi);
  EXPECT_NEAR(c.scans[5].odometry.x, (p5 - p0).x(), 1e-9);  // raw increments, not the particles' mean
}

TEST(Rawlog, BadFilesGiveInputErrors) {
  const auto in = gridtopo::test::syntheticRecords({10});
  const fs::path good = tmpDir() / "good.rawlog";
  writeRawlog(good.string(), in);
  const std::string bytes = readBytes(good);
  // Truncated in the middle of an object.
  const fs::path cut = tmpDir() / "cut.rawlog";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2 + 7);
  try {
    readRawlog(cut.string());
    FAIL() << "truncated rawlog accepted";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.file(), cut.string());
    EXPECT_NE(e.field().find("entry"), std::string::npos);
  }
  // Not a rawlog at all.
  const fs::path text = tmpDir() / "text.rawlog";
  std::ofstream(text) << "FLASER 3 1 2 3 0 0 0 0 0 0 1 host 1\n";
  EXPECT_THROW(readRawlog(text.string()), gridtopo::InputError);
  EXPECT_THROW(readRawlog((tmpDir() / "missing.rawlog").string()), gridtopo::InputError);
  // Empty file: a valid, empty rawlog.
  const fs::path empty = tmpDir() / "empty.rawlog";
  std::ofstream(empty).close();
  EXPECT_EQ(readRawlog(empty.string()).scans.size(), 0u);
}

TEST(Rawlog, FailedWriteLeavesNothingBehind) {
  auto in = gridtopo::test::syntheticRecords({3});
  in[2].scan.ranges.resize(1);
  in[2].scan.valid.resize(1);
  const fs::path p = tmpDir() / "never.rawlog";
  fs::remove(p);
  EXPECT_THROW(writeRawlog(p.string(), in, {}), std::invalid_argument);
  EXPECT_FALSE(fs::exists(p));
  for (const auto& e : fs::directory_iterator(tmpDir()))
    EXPECT_EQ(e.path().filename().string().find(".never.rawlog.tmp"), std::string::npos);
}
