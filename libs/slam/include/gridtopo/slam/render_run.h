#pragma once
// gridtopo-render's run: a log's map re-rendered from a trajectory (trajectory_render.h) in one window (around a
// point, around the trajectory's first loop closure, or the whole map), with the report of what was rendered.
#include <opencv2/core.hpp>

#include <optional>
#include <string>

#include "gridtopo/slam/trajectory_render.h"

namespace gridtopo::slam {

struct RenderRunSpec {
  std::string input;       ///< the log the trajectory was built from
  std::string trajectory;  ///< timestamp x y theta per scan
  std::string config;      ///< SLAM options INI (its beam and map-update options); empty = the defaults
  double resolution = 0.01;  ///< m per cell
  std::optional<std::string> center;  ///< "X Y": the window's centre (m, map frame) ...
  bool loop_closure = false;          ///< ... or the first loop closure's; neither: the whole map
  double size = 8.0;                  ///< window width and height (m)
  double min_travel = 30.0;           ///< loop closure: metres driven between the visits
};

struct RenderRun {
  cv::Mat image;  ///< 8-bit: free white, occupied black, unknown grey
  MapWindow window;
  std::string report_json;  ///< the inputs, the window, the cells, the loop closure and the walls' agreement
  std::string loop_text;    ///< the loop closure and the walls' agreement in a line for people; "" for other windows
};

/// Renders as `spec` says. UsageError for a resolution or size <= 0 or a centre that is not "X Y"; InputError when
/// the trajectory does not fit the log or (loop_closure) never closes a loop.
RenderRun renderRun(const RenderRunSpec& spec);

}  // namespace gridtopo::slam
