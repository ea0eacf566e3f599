#pragma once
// A scan's geometry as MRPT's CObservation2DRangeScan holds it, computed without MRPT's observations: gridtopo-slam
// reads CARMEN logs with it before (and without) loading MRPT's maps and observations. The conversions to and from
// MRPT's class itself are in scan_conversion.h (libgridtopo_io); tests hold the two equal bit for bit.
//
// MRPT describes a planar scan by its field of view ("aperture", a float), its beam count N and its direction: beam
// k points at -aperture/2 + k * aperture/(N-1) (rightToLeft) or +aperture/2 - k * aperture/(N-1), and the laser's
// pose (a CPose3D) carries the fan's centre in its yaw.
#include <mrpt/core/Clock.h>

#include <cstddef>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::io {

/// Seconds (Unix or relative) to MRPT's TTimeStamp, rounded to the nearest 100 ns tick (MRPT's own
/// Clock::fromDouble truncates). MRPT timestamps have a resolution of 100 ns: a timestamp logged with
/// microseconds (CARMEN) survives a round trip exactly, finer digits do not. Throws std::invalid_argument on
/// a non-finite value.
mrpt::Clock::time_point toMrptTime(double seconds);
/// MRPT's TTimeStamp to seconds (mrpt::Clock::toDouble).
double fromMrptTime(mrpt::Clock::time_point t);

/// Why MRPT's CObservation2DRangeScan cannot hold `scan` (fewer than 2 beams, sizes that differ, a zero or
/// non-finite increment, a non-finite pose, timestamp or max range), or null.
const char* whyMrptScanCannotHold(const LaserScan& scan);

/// The increment of `beams` beams spread over MRPT's float `aperture`: the nearest whole number of 1e-4 deg, else
/// of 1e-7 deg, if writing that value gives back the same float aperture; else the float-precision value.
double incrementOfMrptAperture(float aperture, std::size_t beams);

/// The scan's geometry in the form an MRPT CObservation2DRangeScan holds it, its readings untouched: the laser's
/// yaw, the first beam's angle, the increment, the max range and the timestamp become those of
/// fromMrptScan(toMrptScan(scan)) (the fan's centre folded into the yaw, wrapped to (-pi, pi] as CPose3D does, the
/// beams symmetric about it, the max range a float, the time in 100 ns ticks). Every beam points where it pointed,
/// to within rounding; but the same log read from a CARMEN file or fed to the MRPT map builder (gridtopo-map) then
/// gives the filter bit-identical numbers, which the loop closure's discrete decisions need for gridtopo-map to
/// reproduce gridtopo-slam. A scan MRPT cannot hold is left as it is.
void useMrptScanGeometry(LaserScan& scan);

}  // namespace gridtopo::io
