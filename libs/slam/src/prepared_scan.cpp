#include "gridtopo/slam/prepared_scan.h"

#include <cmath>

namespace gridtopo::slam {

PreparedScan prepareScan(const io::LaserScan& scan, const BeamOptions& o, double resolution) {
  PreparedScan p;
  p.sensor = {scan.sensor_pose.x, scan.sensor_pose.y, scan.sensor_pose.phi};
  const double usable =
      o.max_usable_range > 0.0 ? std::min(o.max_usable_range, scan.max_range > 0 ? scan.max_range : 1e9)
                               : scan.max_range;
  const double cs = std::cos(p.sensor.theta), ss = std::sin(p.sensor.theta);
  auto toRobot = [&](double lx, double ly, double& rx, double& ry) {
    rx = p.sensor.x + cs * lx - ss * ly;
    ry = p.sensor.y + ss * lx + cs * ly;
  };
  int step = o.matching_beam_step;
  if (step <= 0) {
    const double inc = std::abs(scan.angle_increment);
    step = inc > 0.0 ? static_cast<int>(std::lround(o.matching_beam_angle / inc)) : 1;
  }
  step = std::max(1, step);
  int hit_count = 0;
  p.map_beams.reserve(scan.size());
  for (std::size_t k = 0; k < scan.size(); ++k) {
    const double r = scan.ranges[k];
    const double a = scan.beamAngle(k);
    const double ca = std::cos(a), sa = std::sin(a);
    double len;
    bool hit;
    if (scan.valid[k] && std::isfinite(r) && r >= o.min_range) {
      hit = r < usable;
      len = hit ? r : usable;
    } else if (o.clear_no_return && !std::isnan(r) && (r >= scan.max_range || std::isinf(r)) && r > 0) {
      hit = false;
      len = std::min(o.no_return_range, usable);
    } else {
      continue;
    }
    MapBeam b{};
    toRobot(len * ca, len * sa, b.ex, b.ey);
    b.hit = hit;
    p.map_beams.push_back(b);
    if (hit && (hit_count++ % step) == 0) {
      double fxr, fyr;
      toRobot((len - resolution) * ca, (len - resolution) * sa, fxr, fyr);
      p.ex.push_back(b.ex);
      p.ey.push_back(b.ey);
      p.fx.push_back(fxr);
      p.fy.push_back(fyr);
    }
  }
  return p;
}

}  // namespace gridtopo::slam
