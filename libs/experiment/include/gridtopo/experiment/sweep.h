#pragma once
// The sweep of an experiment: each swept key has a list of values; the runs are the cartesian product of the
// keys, except that the keys of one zip group advance together (their lists must be equally long). The first key
// in the INI varies slowest, the last fastest; a zip group takes the place of its first key.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace gridtopo::experiment {

struct SweepKey {
  std::string key;
  std::vector<std::string> values;
  std::size_t line = 0;  ///< line in the experiment INI (0 when made in code)
};

/// One run's assignment: (key, value) for every swept key, in the order of the sweep's keys.
using Assignment = std::vector<std::pair<std::string, std::string>>;

/// Splits a value list on white space and expands each `a..b` (integers, a <= b) to a, a+1, ..., b.
/// Throws std::invalid_argument with the reason (empty list, a malformed or descending range). Repeated values are
/// kept: a key in a zip group may repeat a value (`proposal = a a b b`, `particles = 4 8 4 8`); checkDistinct
/// refuses them for a key that is crossed.
std::vector<std::string> parseSweepValues(const std::string& text);

/// std::invalid_argument "value 'v' is listed twice" for the first repeated value.
void checkDistinct(const std::vector<std::string>& values);

/// The runs of the sweep in order. Every key of a zip group must be a key of `keys`, in one group only, and the
/// group's lists must be equally long, a crossed key's values distinct and a zip group's tuples distinct:
/// std::invalid_argument otherwise (the message names the key or the repeated tuple).
std::vector<Assignment> expandSweep(const std::vector<SweepKey>& keys,
                                    const std::vector<std::vector<std::string>>& zip_groups = {});

/// The value of `key` in `a`, or `fallback`.
std::string valueOf(const Assignment& a, const std::string& key, const std::string& fallback = "");

}  // namespace gridtopo::experiment
