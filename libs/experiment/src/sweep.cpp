#include "gridtopo/experiment/sweep.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <stdexcept>

#include "gridtopo/core/ini_value.h"

namespace gridtopo::experiment {

std::vector<std::string> parseSweepValues(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  std::string tok;
  while (in >> tok) {
    const auto dots = tok.find("..");
    if (dots == std::string::npos) {
      out.push_back(tok);
      continue;
    }
    long a = 0, b = 0;
    if (parseIniValue(tok.substr(0, dots), a) || parseIniValue(tok.substr(dots + 2), b))
      throw std::invalid_argument("'" + tok + "' is not a range of integers a..b");
    if (a > b) throw std::invalid_argument("range '" + tok + "' runs backwards");
    if (b - a >= 100000) throw std::invalid_argument("range '" + tok + "' has more than 100000 values");
    for (long v = a; v <= b; ++v) out.push_back(std::to_string(v));
  }
  if (out.empty()) throw std::invalid_argument("no values");
  return out;
}

void checkDistinct(const std::vector<std::string>& values) {
  std::set<std::string> seen;
  for (const auto& v : values)
    if (!seen.insert(v).second) throw std::invalid_argument("value '" + v + "' is listed twice");
}

std::vector<Assignment> expandSweep(const std::vector<SweepKey>& keys,
                                    const std::vector<std::vector<std::string>>& zip_groups) {
  auto indexOf = [&](const std::string& k) -> std::size_t {
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i].key == k) return i;
    throw std::invalid_argument("zip key '" + k + "' is not a swept key");
  };
  // Dimensions: lists of key indices that advance together, ordered by their first key's position.
  std::vector<int> group_of(keys.size(), -1);
  std::vector<std::vector<std::size_t>> dims;
  for (std::size_t g = 0; g < zip_groups.size(); ++g) {
    if (zip_groups[g].size() < 2) throw std::invalid_argument("a zip group needs at least two keys");
    for (const auto& k : zip_groups[g]) {
      const std::size_t i = indexOf(k);
      if (group_of[i] >= 0) throw std::invalid_argument("key '" + k + "' is in two zip groups or twice in one");
      group_of[i] = static_cast<int>(g);
      if (keys[i].values.size() != keys[indexOf(zip_groups[g][0])].values.size())
        throw std::invalid_argument("zip key '" + k + "' has " + std::to_string(keys[i].values.size()) +
                                    " values, '" + zip_groups[g][0] + "' has " +
                                    std::to_string(keys[indexOf(zip_groups[g][0])].values.size()));
    }
  }
  std::vector<bool> placed(zip_groups.size(), false);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (keys[i].values.empty()) throw std::invalid_argument("key '" + keys[i].key + "' has no values");
    if (group_of[i] < 0) {
      dims.push_back({i});
    } else if (!placed[static_cast<std::size_t>(group_of[i])]) {
      placed[static_cast<std::size_t>(group_of[i])] = true;
      std::vector<std::size_t> d;
      for (const auto& k : zip_groups[static_cast<std::size_t>(group_of[i])]) d.push_back(indexOf(k));
      dims.push_back(d);
    }
  }
  for (const auto& d : dims) {
    if (d.size() == 1) {
      try {
        checkDistinct(keys[d[0]].values);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("key '" + keys[d[0]].key + "': " + e.what());
      }
      continue;
    }
    std::set<std::vector<std::string>> tuples;
    for (std::size_t v = 0; v < keys[d[0]].values.size(); ++v) {
      std::vector<std::string> t;
      for (std::size_t i : d) t.push_back(keys[i].values[v]);
      if (!tuples.insert(t).second) {
        std::string what;
        for (std::size_t i : d) what += (what.empty() ? "" : " ") + keys[i].key + "=" + keys[i].values[v];
        throw std::invalid_argument("zip group: '" + what + "' is listed twice");
      }
    }
  }
  std::size_t total = 1;
  for (const auto& d : dims) total *= keys[d[0]].values.size();
  std::vector<Assignment> runs;
  runs.reserve(total);
  std::vector<std::size_t> pos(dims.size(), 0);
  for (std::size_t r = 0; r < total; ++r) {
    std::vector<const std::string*> value(keys.size());
    for (std::size_t d = 0; d < dims.size(); ++d)
      for (std::size_t i : dims[d]) value[i] = &keys[i].values[pos[d]];
    Assignment a;
    for (std::size_t i = 0; i < keys.size(); ++i) a.emplace_back(keys[i].key, *value[i]);
    runs.push_back(std::move(a));
    for (std::size_t d = dims.size(); d-- > 0;) {  // the last dimension advances fastest
      if (++pos[d] < keys[dims[d][0]].values.size()) break;
      pos[d] = 0;
    }
  }
  return runs;
}

std::string valueOf(const Assignment& a, const std::string& key, const std::string& fallback) {
  for (const auto& [k, v] : a)
    if (k == key) return v;
  return fallback;
}

}  // namespace gridtopo::experiment
