// mrpt_builder: an MRPT rawlog -> gridtopo's SLAM -> gridtopo's topology, through the two MRPT map builders.
//
//   mrpt_builder RAWLOG OUTDIR [CONFIG.ini [PLACES_MODEL.yml]]
//
// The rawlog (either MRPT layout: action / sensory-frame pairs or observations, gzip or plain) is read with
// MRPT's own CRawlog over a CFileGZInputStream and fed, entry by entry, to a
// gridtopo::mapping::CMetricMapBuilderTopology wrapping a gridtopo::mapping::CMetricMapBuilderGridRbpf. CONFIG.ini
// may hold a [slam] section (config-ini/slam.ini's keys) and a [topology_builder] section (update_every).
// Writes OUTDIR/map.gridmap.gz (MRPT's COccupancyGridMap2D, serialized), OUTDIR/map.png, OUTDIR/path.txt (the
// positions of the map's scans, gridtopo's trajectory format, for gridtopo-topology -t), OUTDIR/topology.json and OUTDIR/topology.graphml, and prints a
// summary line.
#include <mrpt/config/CConfigFile.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <array>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/mapping/topology_builder.h"
#include "gridtopo/mapping/rbpf_map_builder.h"
#include "gridtopo/topology/export.h"

namespace {

void writeText(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 5) {
    std::fprintf(stderr, "usage: %s RAWLOG OUTDIR [CONFIG.ini [PLACES_MODEL.yml]]\n", argv[0]);
    return 2;
  }
  try {
    const std::string rawlog = argv[1], out = argv[2];
    const std::string model_path = argc > 4 ? argv[4] : GRIDTOPO_PLACES_MODEL;

    // The SLAM builder, wrapped by the topology builder; options from the INI, MRPT style.
    gridtopo::slam::SlamOptions slam_options;
    gridtopo::mapping::TopologyBuilderOptions schedule;
    if (argc > 3) {
      const mrpt::config::CConfigFile ini(argv[3]);
      slam_options.loadFromConfigFile(ini, "slam");
      schedule.loadFromConfigFile(ini, "topology_builder");
    }
    auto slam = std::make_shared<gridtopo::mapping::CMetricMapBuilderGridRbpf>(slam_options);
    auto model = std::make_shared<const gridtopo::places::PlacesModel>(gridtopo::places::PlacesModel::load(model_path));
    gridtopo::mapping::CMetricMapBuilderTopology builder(model, gridtopo::topology::TopologyOptions(), schedule, slam);
    builder.initialize();

    // The rawlog, read with MRPT's classes, one entry at a time.
    if (!std::filesystem::is_regular_file(rawlog)) throw std::runtime_error(rawlog + ": no such file");
    mrpt::io::CFileGZInputStream in(rawlog);
    auto archive = mrpt::serialization::archiveFrom(in);
    mrpt::obs::CActionCollection::Ptr action;
    mrpt::obs::CSensoryFrame::Ptr frame;
    mrpt::obs::CObservation::Ptr obs;
    size_t entry = 0, frames = 0, observations = 0;
    while (mrpt::obs::CRawlog::getActionObservationPairOrObservation(archive, action, frame, obs, entry)) {
      if (obs) {
        builder.processObservation(obs);
        ++observations;
      } else if (action && frame) {
        builder.processActionObservation(*action, *frame);
        ++frames;
      }
      action.reset();
      frame.reset();
      obs.reset();
    }

    if (frames + observations == 0) throw std::runtime_error(rawlog + ": no rawlog entry MRPT could read");

    // The final map and its topology.
    builder.updateTopology();
    const auto topology = builder.currentTopology();
    const auto grid = builder.getCurrentlyBuiltMetricMap()->mapByClass<mrpt::maps::COccupancyGridMap2D>();
    if (!grid || !topology) throw std::runtime_error("the builder made no grid map");

    std::filesystem::create_directories(out);
    {
      mrpt::io::CFileGZOutputStream f(out + "/map.gridmap.gz");
      mrpt::serialization::archiveFrom(f) << *grid;
    }
    grid->saveAsBitmapFile(out + "/map.png");
    mrpt::maps::CSimpleMap path;
    builder.getCurrentlyBuiltMap(path);
    std::vector<gridtopo::TimedPose> poses;
    for (const cv::Point2d& p : gridtopo::mapping::pathOfSimpleMap(path)) poses.push_back({0.0, {p.x, p.y, 0.0}});
    gridtopo::io::writeTrajectory(out + "/path.txt", poses);
    writeText(out + "/topology.json", gridtopo::topology::toJson(topology->graph()));
    writeText(out + "/topology.graphml", gridtopo::topology::toGraphML(topology->graph()));

    // Cells the robot saw (occupancy probability not 0.5), and the graph's nodes per label.
    std::size_t known = 0;
    for (unsigned y = 0; y < grid->getSizeY(); ++y)
      for (unsigned x = 0; x < grid->getSizeX(); ++x) known += grid->getCell(x, y) != 0.5f;
    std::array<int, 3> nodes{0, 0, 0};
    for (const auto& n : topology->graph().nodes) nodes[n.label]++;
    std::printf("mrpt_builder: %zu rawlog entries (%zu frames, %zu observations), %u scans in the map, "
                "map %u x %u cells, %zu known, graph %zu nodes (%d rooms, %d corridors, %d doorways), %zu edges, "
                "%zu topology updates\n",
                entry, frames, observations, builder.getCurrentlyBuiltMapSize(), grid->getSizeX(), grid->getSizeY(),
                known, topology->graph().nodes.size(), nodes[0], nodes[1], nodes[2], topology->graph().edges.size(),
                builder.topologyUpdates());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrpt_builder: error: %s\n", e.what());
    return 1;
  }
}
