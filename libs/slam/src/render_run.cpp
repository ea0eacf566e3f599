#include "gridtopo/slam/render_run.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run_ini.h"

namespace gridtopo::slam {

namespace {

/// The window around the first loop closure, its picture, its report and its line.
void renderAroundLoopClosure(const std::vector<ScanRecord>& scans, const std::vector<TimedPose>& trajectory,
                             const TrajectoryRenderOptions& ro, const RenderRunSpec& spec, RenderRun& out,
                             nlohmann::ordered_json& report) {
  const auto r = renderLoopClosure(scans, trajectory, ro, spec.size, 0.5, spec.min_travel);
  if (!r) throw InputError(spec.trajectory, "no loop closure: the trajectory never comes back within 0.5 m of a "
                                            "pose it left " + std::to_string(spec.min_travel) + " m before");
  const auto& c = r->closure;
  const auto& a = r->agreement;
  report["loop_closure"] = {{"earlier", c.earlier + 1}, {"later", c.later + 1}, {"distance_m", c.distance},
                            {"travelled_m", c.travelled}};
  report["walls_after_vs_before"] = {{"cells", a.cells}, {"median_m", a.median}, {"p90_m", a.p90},
                                     {"within_two_cells", a.within_2cells}};
  std::ostringstream line;
  line << "first loop closure: pose " << c.later + 1 << " comes back " << c.distance << " m from pose "
       << c.earlier + 1 << " after " << c.travelled << " m of travel; walls after it vs before: median "
       << a.median * 100 << " cm, 90th percentile " << a.p90 * 100 << " cm, " << a.within_2cells * 100
       << " % within two cells (" << a.cells << " cells)\n";
  out.loop_text = line.str();
  out.window = r->window;
  out.image = renderWindow(r->map, out.window);
}

}  // namespace

RenderRun renderRun(const RenderRunSpec& spec) {
  if (spec.resolution <= 0 || spec.size <= 0) throw UsageError("--resolution and --size must be > 0");
  const SlamOptions so = spec.config.empty() ? SlamOptions{} : loadSlamOptionsIni(spec.config);
  const auto trajectory = io::readTrajectory(spec.trajectory);
  const auto scans = io::readScanLog(spec.input);
  TrajectoryRenderOptions ro;
  ro.resolution = spec.resolution;
  ro.beams = so.beams;
  ro.map = so.map;
  nlohmann::ordered_json report{{"input", spec.input}, {"trajectory", spec.trajectory}, {"resolution", ro.resolution}};
  RenderRun out;
  try {
    if (spec.loop_closure) {
      renderAroundLoopClosure(scans, trajectory, ro, spec, out, report);
    } else {
      if (spec.center) {
        std::istringstream in(*spec.center);
        double x = 0, y = 0;
        if (!(in >> x >> y)) throw UsageError("--center: expected \"X Y\", got \"" + *spec.center + "\"");
        ro.window = MapWindow::around(x, y, spec.size, spec.size);
      }
      const GridMap map = mapFromTrajectory(scans, trajectory, ro);
      out.window = ro.window ? *ro.window : boundsOf(map);
      out.image = renderWindow(map, out.window);
    }
  } catch (const TrajectoryMismatch& e) {
    throw InputError(spec.trajectory, 0, "timestamp", e.what());
  }
  report["window_m"] = {out.window.x0, out.window.y0, out.window.x1, out.window.y1};
  report["cells"] = {out.image.cols, out.image.rows};
  out.report_json = report.dump(2) + "\n";
  return out;
}

}  // namespace gridtopo::slam
