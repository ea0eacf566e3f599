#include "test_tmp_dir.h"
#include "gridtopo/io/map_io.h"

#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/scan_conversion.h"
#include "synthetic_scans.h"

namespace fs = std::filesystem;
using namespace gridtopo::io;
using mrpt::maps::COccupancyGridMap2D;

using gridtopo::test::tmpDir;
using gridtopo::test::readText;

namespace {
const fs::path kMaps = fs::path(GRIDTOPO_DATA_DIR) / "places" / "maps";

// A 40 x 30 grid with free, occupied, unknown and intermediate cells, its lower-left corner at (x0, y0).
COccupancyGridMap2D::Ptr sampleGrid(float x0, float y0, float res = 0.05f) {
  auto g = COccupancyGridMap2D::Create();
  g->setSize(x0, x0 + 40 * res, y0, y0 + 30 * res, res, 0.5f);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      float p = 0.5f;
      if (x == 0 || y == 0 || x == 39)
        p = 0.0f;  // walls (occupied)
      else if (y < 20)
        p = 1.0f;  // free
      else if (x == 7 && y == 25)
        p = 0.3f;
      g->setCell(x, y, p);
    }
  return g;
}

void expectSameCells(const COccupancyGridMap2D& a, const COccupancyGridMap2D& b) {
  ASSERT_EQ(a.getSizeX(), b.getSizeX());
  ASSERT_EQ(a.getSizeY(), b.getSizeY());
  EXPECT_EQ(a.getRawMap(), b.getRawMap());
}
}  // namespace

TEST(MapIo, PlacesMapsReadWithTheirSizeAndGoBackToTheSameImage) {
  std::size_t maps = 0;
  for (const auto& e : fs::directory_iterator(kMaps)) {
    if (e.path().extension() != ".png") continue;
    SCOPED_TRACE(e.path().filename().string());
    ++maps;
    const cv::Mat src = cv::imread(e.path().string(), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(src.empty());
    const auto g = readGridMap(e.path().string());  // plain image: 0.05 m, origin (0, 0)
    EXPECT_EQ(g->getResolution(), 0.05f);
    EXPECT_EQ(g->getXMin(), 0.0f);
    EXPECT_EQ(g->getYMin(), 0.0f);
    ASSERT_EQ(static_cast<int>(g->getSizeX()), src.cols);
    ASSERT_EQ(static_cast<int>(g->getSizeY()), src.rows);
    // The top-left pixel is the cell with the largest y, smallest x.
    const cv::Mat back = gridToImage(*g);
    ASSERT_EQ(back.size(), src.size());
    std::size_t exact = 0, near_free = 0, mismatches = 0;
    int worst_other = 0;
    for (int r = 0; r < src.rows; ++r)
      for (int c = 0; c < src.cols; ++c) {
        const int s = src.at<uint8_t>(r, c), b = back.at<uint8_t>(r, c);
        if (s == 0 || s == 255) {
          exact += s == b;
          mismatches += s != b;
        } else if (s == 254) {
          near_free += b >= 250;
          mismatches += b < 250;
        } else {
          worst_other = std::max(worst_other, std::abs(s - b));
        }
        // Occupancy at that pixel, through MRPT's own world -> cell lookup: pixel centre in metres.
        if ((r * 7 + c * 13) % 997 == 0) {
          const float x = (static_cast<float>(c) + 0.5f) * 0.05f;
          const float y = (static_cast<float>(src.rows - 1 - r) + 0.5f) * 0.05f;
          EXPECT_NEAR(g->getPos(x, y), s / 255.0, 0.02);
        }
      }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(exact + near_free, static_cast<std::size_t>(src.total() / 4));
    // Other greys come back within the 8-bit log-odds quantisation of MRPT's cells.
    EXPECT_LE(worst_other, 4);
  }
  EXPECT_EQ(maps, 27u);
}

TEST(MapIo, LabIntelOriginalHasKnownSizeAndFreeArea) {
  const auto g = readGridMap((kMaps / "lab_intel_original.png").string());
  const cv::Mat img = cv::imread((kMaps / "lab_intel_original.png").string(), cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(static_cast<int>(g->getSizeX()), img.cols);
  EXPECT_EQ(static_cast<int>(g->getSizeY()), img.rows);
  // Free cells (grey >= 250 in the benchmark's convention) are exactly those with p_free >= 250/255.
  std::size_t free_img = 0, free_grid = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      free_img += img.at<uint8_t>(r, c) >= 250;
      free_grid += g->getCell(c, img.rows - 1 - r) >= 250.0f / 255.0f;
    }
  EXPECT_GT(free_img, 1000u);
  EXPECT_EQ(free_grid, free_img);
}

TEST(MapIo, PngRoundTripIsExact) {
  const auto g = sampleGrid(0.0f, 0.0f);
  const fs::path p = tmpDir() / "grid.png";
  writeMapPng(*g, p.string());
  const cv::Mat img = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(img.type(), CV_8UC1);
  EXPECT_EQ(img.cols, 40);
  EXPECT_EQ(img.rows, 30);
  EXPECT_EQ(img.at<uint8_t>(29, 5), 0);    // bottom row (y = 0): wall
  EXPECT_EQ(img.at<uint8_t>(28, 5), 255);  // free
  EXPECT_EQ(img.at<uint8_t>(0, 5), 128);   // unknown: round(255 * 0.5)
  MapReadOptions opt;
  const auto back = readGridMap(p.string(), opt);
  // Free/occupied/unknown cells come back bit-identical; the 0.3 cell within one grey level.
  EXPECT_EQ(back->getCell(5, 0), g->getCell(5, 0));
  EXPECT_EQ(back->getCell(5, 1), g->getCell(5, 1));
  EXPECT_NEAR(back->getCell(7, 25), g->getCell(7, 25), 0.01);
  EXPECT_EQ(gridToImage(*back).size(), cv::Size(40, 30));
  cv::Mat diff;
  cv::absdiff(gridToImage(*back), img, diff);
  EXPECT_LE(cv::norm(diff, cv::NORM_INF), 1.0);
}

TEST(MapIo, RosMapRoundTripKeepsExactOriginAndResolution) {
  // A gmapping-style origin half a cell off the resolution grid: MRPT's setSize() alone would move it.
  const float x0 = -51.225f, y0 = -12.375f;
  auto g = sampleGrid(0.0f, 0.0f);
  const auto g2 = readGridMap(
      [&] {
        const fs::path png = tmpDir() / "tmp_src.png";
        writeMapPng(*g, png.string());
        return png.string();
      }(),
      MapReadOptions{0.05, x0, y0});
  EXPECT_EQ(g2->getXMin(), x0);
  EXPECT_EQ(g2->getYMin(), y0);
  const fs::path stem = tmpDir() / "rosmap";
  writeRosMap(*g2, stem.string());
  EXPECT_EQ(readText(stem.string() + ".yaml"),
            "image: rosmap.pgm\nresolution: 0.05\norigin: [-51.225, -12.375, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const cv::Mat pgm = cv::imread(stem.string() + ".pgm", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(pgm.size(), cv::Size(40, 30));
  EXPECT_EQ(pgm.at<uint8_t>(29, 5), 0);
  EXPECT_EQ(pgm.at<uint8_t>(28, 5), 254);
  EXPECT_EQ(pgm.at<uint8_t>(0, 5), 205);
  EXPECT_EQ(pgm.at<uint8_t>(29 - 25, 7), 0);  // p_free 0.3: p_occ 0.7 > occupied_thresh
  const auto back = readGridMap(stem.string() + ".yaml");
  EXPECT_EQ(back->getResolution(), 0.05f);
  EXPECT_EQ(back->getXMin(), x0);
  EXPECT_EQ(back->getYMin(), y0);
  EXPECT_EQ(back->getSizeX(), 40u);
  EXPECT_EQ(back->getSizeY(), 30u);
  EXPECT_FLOAT_EQ(back->getXMax(), x0 + 40 * 0.05f);
  // World -> cell lookups agree with the source grid.
  EXPECT_EQ(back->x2idx(x0 + 0.26f), 5);
  EXPECT_LT(back->getCell(5, 0), 0.01f);
  EXPECT_GT(back->getCell(5, 1), 0.99f);
  EXPECT_EQ(back->getCell(5, 29), 0.5f);
  // The .pgm read directly finds its .yaml beside it.
  const auto viaPgm = readGridMap(stem.string() + ".pgm");
  EXPECT_EQ(viaPgm->getXMin(), x0);
  expectSameCells(*back, *viaPgm);
}

TEST(MapIo, RosMapServerSemantics) {
  const fs::path d = tmpDir() / "ros_semantics";
  fs::create_directories(d);
  cv::Mat img(1, 6, CV_8UC1);
  const uint8_t px[6] = {0, 50, 100, 205, 230, 255};
  for (int i = 0; i < 6; ++i) img.at<uint8_t>(0, i) = px[i];
  cv::imwrite((d / "m.pgm").string(), img);
  auto cells = [&](const std::string& extra) {
    std::ofstream(d / "m.yaml") << "image: m.pgm\nresolution: 0.1\norigin: [1.5, -2.0, 0.0]\n"
                                << "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
                                << extra;
    const auto g = readGridMap((d / "m.yaml").string());
    std::vector<float> v;
    for (int i = 0; i < 6; ++i) v.push_back(g->getCell(i, 0));
    return v;
  };
  // trinary, negate 0: occupancy (255 - v) / 255 = 1, .80, .61, .196, .098, 0.
  auto t = cells("negate: 0\n");
  EXPECT_LT(t[0], 0.01f);
  EXPECT_LT(t[1], 0.01f);  // 0.80 > 0.65: occupied
  EXPECT_EQ(t[2], 0.5f);   // 0.61: unknown
  EXPECT_EQ(t[3], 0.5f);   // 0.196 is not < 0.196: unknown (map_saver's 205)
  EXPECT_GT(t[4], 0.99f);  // free
  EXPECT_GT(t[5], 0.99f);
  auto n = cells("negate: 1\n");  // occupancy v / 255
  EXPECT_GT(n[0], 0.99f);
  EXPECT_LT(n[5], 0.01f);
  auto s = cells("mode: scale\n");  // 0.61 -> p_free = 1 - (0.61 - 0.196) / (0.65 - 0.196) = 0.088
  EXPECT_NEAR(s[2], 1.0 - ((255.0 - 100.0) / 255.0 - 0.196) / (0.65 - 0.196), 0.03);
  auto r = cells("mode: raw\n");  // v = percent occupied: 0 -> free, 50 -> 0.5, 100 -> occupied, more -> unknown
  EXPECT_GT(r[0], 0.99f);
  EXPECT_NEAR(r[1], 0.5f, 0.01f);
  EXPECT_LT(r[2], 0.01f);
  EXPECT_EQ(r[3], 0.5f);
  // Bad YAML: the key is named.
  std::ofstream(d / "bad.yaml") << "image: m.pgm\nresolution: -1\norigin: [0, 0, 0]\n";
  try {
    readGridMap((d / "bad.yaml").string());
    FAIL();
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.field(), "resolution");
  }
  std::ofstream(d / "bad2.yaml") << "image: m.pgm\nresolution: 0.05\norigin: [0, 0]\n";
  EXPECT_THROW(readGridMap((d / "bad2.yaml").string()), gridtopo::InputError);
  std::ofstream(d / "bad3.yaml") << "image: missing.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  EXPECT_THROW(readGridMap((d / "bad3.yaml").string()), gridtopo::InputError);
  std::ofstream(d / "bad4.yaml") << "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0.5]\n";
  EXPECT_THROW(readGridMap((d / "bad4.yaml").string()), gridtopo::InputError);
}

TEST(MapIo, GridmapGzRoundTripAndMrptCanLoadIt) {
  const auto g = sampleGrid(-3.0f, 2.5f);
  const fs::path p = tmpDir() / "grid.gridmap.gz";
  writeGridmapGz(*g, p.string());
  const auto back = readGridMap(p.string());
  EXPECT_EQ(back->getResolution(), 0.05f);
  EXPECT_EQ(back->getXMin(), -3.0f);
  EXPECT_EQ(back->getYMin(), 2.5f);
  expectSameCells(*g, *back);
  // MRPT's own way of reading it (what its tools do).
  mrpt::io::CFileGZInputStream in(p.string());
  COccupancyGridMap2D m;
  mrpt::serialization::archiveFrom(in) >> m;
  expectSameCells(*g, m);
  // Not a grid inside: a clear error.
  const fs::path other = tmpDir() / "not_a_grid.gridmap.gz";
  {
    mrpt::io::CFileGZOutputStream out(other.string());
    mrpt::serialization::archiveFrom(out) << mrpt::maps::CSimpleMap();
  }
  EXPECT_THROW(readGridMap(other.string()), gridtopo::InputError);
  std::ofstream(tmpDir() / "junk.gridmap") << "junk";
  EXPECT_THROW(readGridMap((tmpDir() / "junk.gridmap").string()), gridtopo::InputError);
}

TEST(MapIo, CorruptedGridmapGivesAnInputErrorOrAMapNeverACrash) {
  // Byte flips in an uncompressed .gridmap (MRPT's serialised COccupancyGridMap2D): MRPT's deserialiser runs in a
  // child process first (isolated_parse.h), so a flip in a size field cannot crash or exhaust the memory.
  const auto g = sampleGrid(-3.0f, 2.5f);
  const fs::path clean = tmpDir() / "flip_clean.gridmap";
  {
    mrpt::io::CFileOutputStream out(clean.string());  // plain: the flips reach MRPT's data
    mrpt::serialization::archiveFrom(out) << *g;
  }
  std::ifstream f(clean, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(f), {}};
  ASSERT_GT(bytes.size(), 100u);
  std::mt19937 rng(4242);
  int parsed = 0, errors = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::string mutated = bytes;
    // Flips within the first 120 bytes: MRPT's object header, class name, version, sizes and limits.
    for (int k = 0; k < 2; ++k) mutated[rng() % 120] ^= static_cast<char>(1 + rng() % 255);
    const fs::path p = tmpDir() / "flipped.gridmap";
    std::ofstream(p, std::ios::binary) << mutated;
    try {
      readGridMap(p.string());
      ++parsed;
    } catch (const gridtopo::InputError& e) {
      ++errors;
      EXPECT_EQ(e.file(), p.string());
    }
  }
  EXPECT_EQ(parsed + errors, 60);
  EXPECT_GT(errors, 20);
}

TEST(MapIo, SimplemapIsWrittenAsMrptReadsIt) {
  const auto recs = gridtopo::test::syntheticRecords({5});
  mrpt::maps::CSimpleMap sm;
  for (const auto& r : recs) {
    auto sf = mrpt::obs::CSensoryFrame::Create();
    sf->insert(toMrptScan(r.scan));
    const mrpt::poses::CPose3D pose(r.odometry.x, r.odometry.y, 0.0, r.odometry.phi, 0.0, 0.0);
    sm.insert(mrpt::poses::CPose3DPDFGaussian::Create(pose, mrpt::math::CMatrixDouble66()), sf);
  }
  const fs::path p = tmpDir() / "map.simplemap";
  writeSimplemap(sm, p.string());
  mrpt::maps::CSimpleMap back;
  ASSERT_TRUE(back.loadFromFile(p.string()));
  ASSERT_EQ(back.size(), 5u);
  mrpt::poses::CPose3DPDF::Ptr pose;
  mrpt::obs::CSensoryFrame::Ptr sf;
  back.get(3, pose, sf);
  EXPECT_NEAR(pose->getMeanVal().x(), recs[3].odometry.x, 1e-12);
  ASSERT_TRUE(sf);
  EXPECT_EQ(sf->getObservationByClass<mrpt::obs::CObservation2DRangeScan>()->getScanSize(), 180u);
}

TEST(MapIo, WriteGridMapPicksTheFormatAndFailsCleanly) {
  const auto g = sampleGrid(0.0f, 0.0f);
  const fs::path d = tmpDir() / "by_name";
  writeGridMap(*g, (d / "a.png").string());
  writeGridMap(*g, (d / "b.yaml").string());
  writeGridMap(*g, (d / "c.gridmap.gz").string());
  EXPECT_TRUE(fs::exists(d / "a.png"));
  EXPECT_TRUE(fs::exists(d / "b.pgm"));
  EXPECT_TRUE(fs::exists(d / "b.yaml"));
  EXPECT_TRUE(fs::exists(d / "c.gridmap.gz"));
  EXPECT_THROW(writeGridMap(*g, (d / "d.txt").string()), std::invalid_argument);
  // A ROS map whose directory cannot be created: neither file appears.
  std::ofstream(d / "file").close();
  EXPECT_ANY_THROW(writeRosMap(*g, (d / "file" / "m").string()));
  EXPECT_FALSE(fs::exists(d / "file" / "m.pgm"));
  EXPECT_THROW(readGridMap((d / "missing.png").string()), gridtopo::InputError);
  std::ofstream(d / "not_an_image.png") << "hello";
  EXPECT_THROW(readGridMap((d / "not_an_image.png").string()), gridtopo::InputError);
}

TEST(MapIo, GridmapWithOriginOffTheCellGridKeepsItsExactOrigin) {
  // MRPT's own loader (COccupancyGridMap2D deserialiser -> setSize()) moves an origin that is not a whole
  // number of cells by up to half a cell; readGridMap gives the stored origin back.
  const fs::path png = tmpDir() / "snap_src.png";
  writeMapPng(*sampleGrid(0.0f, 0.0f), png.string());
  const auto g = readGridMap(png.string(), MapReadOptions{0.05, -51.225, -12.375});
  ASSERT_EQ(g->getXMin(), -51.225f);
  const fs::path p = tmpDir() / "snap.gridmap.gz";
  writeGridmapGz(*g, p.string());
  const auto back = readGridMap(p.string());
  EXPECT_EQ(back->getXMin(), -51.225f);
  EXPECT_EQ(back->getYMin(), -12.375f);
  EXPECT_EQ(back->getSizeX(), 40u);
  EXPECT_EQ(back->getSizeY(), 30u);
  expectSameCells(*g, *back);
  mrpt::io::CFileGZInputStream in(p.string());
  COccupancyGridMap2D m;
  mrpt::serialization::archiveFrom(in) >> m;
  EXPECT_NEAR(m.getXMin(), -51.2f, 1e-5);  // MRPT itself: half a cell off
  EXPECT_NEAR(m.getYMin(), -12.4f, 1e-5);
}

TEST(MapIo, MapFileKindFollowsTheReader) {
  using gridtopo::MapKind;
  using gridtopo::io::mapFileKind;
  EXPECT_EQ(mapFileKind("a/map.gridmap"), MapKind::ProbabilisticGrid);
  EXPECT_EQ(mapFileKind("a/MAP.GRIDMAP.GZ"), MapKind::ProbabilisticGrid);
  EXPECT_EQ(mapFileKind("a/map.yaml"), MapKind::RosMap);
  EXPECT_EQ(mapFileKind("a/map.YML"), MapKind::RosMap);
  const fs::path d = tmpDir() / "kind";
  fs::create_directories(d);
  std::ofstream(d / "plan.png") << "x";
  EXPECT_EQ(mapFileKind((d / "plan.png").string()), MapKind::PlainImage);
  std::ofstream(d / "plan.yaml") << "image: plan.png\n";
  EXPECT_EQ(mapFileKind((d / "plan.png").string()), MapKind::RosMap);  // a .yaml beside the image
}

TEST(MapIo, ReadMapReturnsTheTypedMapWithTheKindOfItsFormat) {
  // A plain image, the same map as a .gridmap.gz: the same grey image and origin, the kind from the reader.
  const fs::path d = tmpDir() / "typed";
  fs::create_directories(d);
  const fs::path png = d / "m.png";
  writeMapPng(*sampleGrid(0.0f, 0.0f), png.string());
  const gridtopo::MapImage plain = gridtopo::io::readMap(png.string(), MapReadOptions{0.05, -1.5, 2.25});
  EXPECT_EQ(plain.kind, gridtopo::MapKind::PlainImage);
  EXPECT_EQ(plain.source, png.string());
  EXPECT_EQ(plain.grey.size(), cv::Size(40, 30));
  EXPECT_DOUBLE_EQ(plain.resolution, 0.05f);
  EXPECT_DOUBLE_EQ(plain.origin.x, -1.5);
  EXPECT_DOUBLE_EQ(plain.origin.y, 2.25);
  const auto grid = readGridMap(png.string(), MapReadOptions{0.05, -1.5, 2.25});
  writeGridmapGz(*grid, (d / "m.gridmap.gz").string());
  const gridtopo::MapImage prob = gridtopo::io::readMap((d / "m.gridmap.gz").string());
  EXPECT_EQ(prob.kind, gridtopo::MapKind::ProbabilisticGrid);
  EXPECT_EQ(cv::countNonZero(prob.grey != plain.grey), 0);
  EXPECT_DOUBLE_EQ(prob.origin.x, -1.5);
  // Whoever builds a map names its kind: mapImageOfGrid keeps it.
  const auto built = gridtopo::io::mapImageOfGrid(*grid, gridtopo::MapKind::ProbabilisticGrid, "<slam map>");
  EXPECT_EQ(built.kind, gridtopo::MapKind::ProbabilisticGrid);
  EXPECT_EQ(built.source, "<slam map>");
  EXPECT_EQ(cv::countNonZero(built.grey != plain.grey), 0);
}
