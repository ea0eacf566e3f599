#pragma once
// The kind of a map, kept with the map data (a small header: topology options and the GUI session use it without
// the MRPT map types).

namespace gridtopo::io {

/// What a map is, which decides how its grey levels (gridToImage) are read as free space
/// (topology::TopologyOptions::freeThresholdFor / freeOpeningRadiusFor): a plain image (a drawn plan), a ROS
/// map_server map (0 / 205 / 254 greys), or an MRPT probabilistic grid (a .gridmap(.gz) file or a map the SLAM
/// built, whose clamped log-odds never reach grey 250). It travels with the map (e.g. session::MapLayer::kind):
/// only a file's kind is read from its name.
enum class MapKind { PlainImage, RosMap, ProbabilisticGrid };

}  // namespace gridtopo::io
