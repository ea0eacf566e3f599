#pragma once
// Ground-truth relations of the Freiburg SLAM benchmark (Kümmerle et al., "On measuring the accuracy of SLAM
// algorithms", Autonomous Robots 27(4), 2009): "t1 t2 x y z roll pitch yaw" per line, the pose at t2 in the
// frame of the pose at t1, timestamps being the ipc_timestamp of laser lines.
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <string>
#include <vector>

namespace gridtopo::eval {

struct Relation {
  double t1 = 0.0, t2 = 0.0;               ///< seconds (ipc timestamps); t2 < t1 is allowed
  mrpt::math::TPose2D delta{0, 0, 0};      ///< reference p(t1)⁻¹ ⊕ p(t2): x, y and yaw
  std::size_t line = 0;                    ///< 1-based line in the relations file
};

/// Reads a relations file, plain or gzip. z, roll and pitch must be numbers (they are ignored: planar metric).
/// Throws gridtopo::InputError naming file, line and field on malformed lines or a truncated gzip file.
std::vector<Relation> readRelations(const std::string& path);
/// Parses relations text (already decompressed); `name` is used in error messages.
std::vector<Relation> parseRelations(const std::string& text, const std::string& name);

/// Reads a whole text file, transparently decompressing gzip; a truncated or corrupt gzip file is an
/// InputError (never a silently shortened text).
std::string readMaybeGzipped(const std::string& path);

}  // namespace gridtopo::eval
