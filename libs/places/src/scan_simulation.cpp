#include "gridtopo/places/scan_simulation.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

std::string beamStopName(BeamStop b) {
  switch (b) {
    case BeamStop::kObstacle: return "obstacle";
    case BeamStop::kMaxRange: return "max_range";
    case BeamStop::kPass: return "pass";
  }
  return "?";
}

BeamStop parseBeamStop(const std::string& text, const std::string& where, const std::string& key, bool allow_pass) {
  if (text == "obstacle") return BeamStop::kObstacle;
  if (text == "max_range") return BeamStop::kMaxRange;
  if (text == "pass" && allow_pass) return BeamStop::kPass;
  throw InputError(where, 0, key,
                   "must be obstacle or max_range" + std::string(allow_pass ? " or pass" : "") + ", got '" + text + "'");
}

const OptionSchema<ScanSimulationOptions>& scanSimulationOptionSchema() {
  using O = ScanSimulationOptions;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::places::ScanSimulationOptions")
          .add("num_beams", &O::num_beams, OptionRange::closed(8, 3600), "beams",
               "beams per simulated scan, a multiple of 4 (360 = 1 degree apart)")
          .add("max_range", &O::max_range, OptionRange::leftOpen(0, 65), "m", "longer beams are capped here")
          .add("lattice_spacing", &O::lattice_spacing, OptionRange::closed(0, 2), "m",
               "between classified cells (block side); <= the resolution = every cell")
          .add("threads", &O::threads, OptionRange::closed(1, 256), "", "worker threads (results do not depend on it)")
          .addWords<BeamStop>("unknown_cells", field(&O::unknown_cells),
                              {{"obstacle", BeamStop::kObstacle}, {"max_range", BeamStop::kMaxRange},
                               {"pass", BeamStop::kPass}},
                              "a beam that meets an unknown cell ends there, reads max_range or passes through")
          .addWords<BeamStop>("map_border", field(&O::map_border),
                              {{"obstacle", BeamStop::kObstacle}, {"max_range", BeamStop::kMaxRange}},
                              "a beam that leaves the image ends there or reads max_range")
          .rule("num_beams", [](const O& o) -> std::optional<std::string> {
            if (o.num_beams % 4 == 0) return std::nullopt;
            return "must be a multiple of 4, got " + std::to_string(o.num_beams);
          });
  return schema;
}


Lattice buildLattice(const OccupancyImage& occ, double lattice_spacing) {
  Lattice lat;
  lat.stride = std::max(1, static_cast<int>(std::lround(lattice_spacing / occ.resolution)));
  const int s = lat.stride;
  const int br = (occ.rows() + s - 1) / s, bc = (occ.cols() + s - 1) / s;
  lat.block_sample = cv::Mat(br, bc, CV_32S, cv::Scalar(-1));
  const double mid = (s - 1) / 2.0;
  for (int by = 0; by < br; ++by)
    for (int bx = 0; bx < bc; ++bx) {
      int best_r = -1, best_c = -1;
      double best_d = 1e18;
      for (int r = by * s; r < std::min(occ.rows(), by * s + s); ++r)
        for (int c = bx * s; c < std::min(occ.cols(), bx * s + s); ++c) {
          if (!occ.isFree(r, c)) continue;
          const double d = (r - by * s - mid) * (r - by * s - mid) + (c - bx * s - mid) * (c - bx * s - mid);
          if (d < best_d) best_d = d, best_r = r, best_c = c;
        }
      if (best_r < 0) continue;
      lat.block_sample.at<int>(by, bx) = static_cast<int>(lat.samples.size());
      lat.samples.emplace_back(best_c, best_r);
      lat.blocks.emplace_back(bx, by);
    }
  return lat;
}

namespace {

// The samples of each column of an image (CSR): (row, sample index) of column k are
// items[begin[k]] .. items[begin[k + 1] - 1], in increasing row.
struct ColumnSamples {
  std::vector<int> begin;
  std::vector<std::pair<int, int>> items;
};

ColumnSamples samplesByColumn(const std::vector<cv::Point>& samples, int cols, bool transposed) {
  ColumnSamples cs;
  cs.begin.assign(static_cast<std::size_t>(cols) + 1, 0);
  for (const cv::Point& p : samples) cs.begin[static_cast<std::size_t>(transposed ? p.y : p.x) + 1]++;
  for (int k = 0; k < cols; ++k) cs.begin[static_cast<std::size_t>(k) + 1] += cs.begin[static_cast<std::size_t>(k)];
  cs.items.resize(samples.size());
  std::vector<int> fill(cs.begin.begin(), cs.begin.end() - 1);
  std::vector<std::size_t> order(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) order[i] = i;
  // Increasing row within a column: sort by (row) stably; the samples come in block-row order already, so a
  // stable sort keeps ties (none: one sample per cell) in index order.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return (transposed ? samples[a].x : samples[a].y) < (transposed ? samples[b].x : samples[b].y);
  });
  for (std::size_t i : order) {
    const cv::Point& p = samples[i];
    const int col = transposed ? p.y : p.x, row = transposed ? p.x : p.y;
    cs.items[static_cast<std::size_t>(fill[static_cast<std::size_t>(col)]++)] = {row, static_cast<int>(i)};
  }
  return cs;
}

// Spans covering the cells a beam passes as free (kFree, kSeen) in each row of an image (CSR): the spans of row k
// are [runs[i].first, runs[i].second) for i in begin[k] .. begin[k + 1] - 1, increasing and disjoint. Free runs
// less than kRunGap cells apart share a span (a span may hold non-free cells: the sweep's loop over a span is
// vectorised, and SLAM maps have many short free runs).
struct RowRuns {
  std::vector<int> begin;
  std::vector<std::pair<int, int>> runs;
};

constexpr int kRunGap = 64;

RowRuns freeRunsOfRows(const cv::Mat& image) {
  RowRuns rr;
  rr.begin.assign(static_cast<std::size_t>(image.rows) + 1, 0);
  for (int k = 0; k < image.rows; ++k) {
    const unsigned char* c = image.ptr<unsigned char>(k);
    for (int m = 0; m < image.cols;) {
      if (c[m] != kFree && c[m] != kSeen) {
        ++m;
        continue;
      }
      const int a = m;
      while (m < image.cols && (c[m] == kFree || c[m] == kSeen)) ++m;
      if (rr.runs.size() > static_cast<std::size_t>(rr.begin[static_cast<std::size_t>(k)]) &&
          a - rr.runs.back().second < kRunGap)
        rr.runs.back().second = m;
      else
        rr.runs.emplace_back(a, m);
    }
    rr.begin[static_cast<std::size_t>(k) + 1] = static_cast<int>(rr.runs.size());
  }
  return rr;
}

// One family of parallel digital lines along the columns of an image (the caller swaps the roles of rows and
// columns for steep directions): the row of line j at column k is j + offset[k], offset[k] = floor(k * slope +
// 0.5), |slope| <= 1. Every cell lies on exactly one line. A forward sweep (k increasing) measures the free run
// behind each cell (the beam pointing to decreasing k), a backward sweep the run ahead.
// The sweeps go column by column over all lines at once (`columns` holds the image's column k as its row k, so
// it is read in memory order) with one run counter per line; the run lengths are those of walking each line on
// its own (as this function did until 2026-12), without the cache misses of following a slanted line.
// What an unknown cell and the border do to the counter (ScanSimulationOptions::unknown_cells, map_border): an
// obstacle resets it to 0, max range saturates it (the beam from any later cell of the line reads max range until
// the next obstacle), pass counts the unknown cell as free.
// `k0`: the image's index of column 0 of `columns` (a window of the image's rows, see simulateBeams): the lines
// are those of the whole image.
struct Family {
  double slope = 0;
  int beam_back = 0, beam_ahead = 0;
};

// Several families swept together (sweepFamilies): each column is read once for all of them while it is in
// the cache (one family at a time read the whole image from memory once per pass and direction pair).
struct FamilyState {
  std::vector<int> offset;
  int max_off = 0, max_run = 0;
  std::vector<std::uint16_t> mm;
  std::vector<int> run;
};

// The counters of n lines over their next cells c (obstacle and unknown cells reset them), in its own function
// so that the loop is vectorised (no pointer of the caller aliases r), and built twice: AVX2 (eight counters a
// step) where the CPU has it, else SSE2 (integers: the same counters either way).
__attribute__((target_clones("avx2", "default"))) void advanceFree(int* __restrict r, const unsigned char* __restrict c, int n, int max_run) {
  for (int m = 0; m < n; ++m) r[m] = (c[m] == kFree || c[m] == kSeen) ? std::min(r[m] + 1, max_run) : 0;
}

// `free_runs` (freeRunsOfRows of `columns`): when unknown cells and the border stop a beam as an obstacle, a
// counter is non-zero only on a line whose last cell was free, so each column updates only the lines through
// its own free spans and through the previous column's (one row wider on either side: a line moves by at most one
// row from column to column): every other counter is 0 and stays 0. The sweep then costs about the free cells,
// not the image; the counters are the same.
void sweepFamilies(const cv::Mat& columns, const ColumnSamples& samples, const RowRuns& free_runs, double resolution,
                   const std::vector<Family>& families, int k0, double max_range_mm, BeamStop unknown_cells,
                   BeamStop map_border, cv::Mat& by_beam) {
  const int n_major = columns.rows, n_minor = columns.cols;
  const bool unknown_default = unknown_cells == BeamStop::kObstacle;
  const bool sparse = unknown_default && map_border == BeamStop::kObstacle;
  std::vector<FamilyState> state(families.size());
  for (std::size_t f = 0; f < families.size(); ++f) {
    FamilyState& st = state[f];
    const double slope = families[f].slope;
    st.offset.resize(static_cast<std::size_t>(n_major));
    for (int k = 0; k < n_major; ++k)
      st.offset[static_cast<std::size_t>(k)] = static_cast<int>(std::floor((k + k0) * slope + 0.5));
    const int min_off = *std::min_element(st.offset.begin(), st.offset.end());
    st.max_off = *std::max_element(st.offset.begin(), st.offset.end());
    const double step_mm = resolution * 1000.0 * std::sqrt(1.0 + slope * slope);
    // Run lengths in steps, converted to mm through a small table (runs beyond max range saturate).
    st.max_run = static_cast<int>(max_range_mm / step_mm) + 2;
    st.mm.resize(static_cast<std::size_t>(st.max_run) + 1);
    for (int r = 0; r <= st.max_run; ++r)
      st.mm[static_cast<std::size_t>(r)] =
          static_cast<std::uint16_t>(std::lround(std::min((r + 0.5) * step_mm, max_range_mm)));
    // run[j + max_off]: free cells of line j passed since its last non-free cell (or since it entered the
    // image), saturated at max_run (only min(run, max_run) is used). A line is inside the image for one interval
    // of k, so its counter is untouched (0) until it enters.
    st.run.resize(static_cast<std::size_t>(n_minor + st.max_off - min_off));
  }
  // A line enters the image with the counter of the border; each cell state maps the counter r to its next value
  // through max(r + add, floor) capped at max_run: free (+1, 0), occupied (reset: -inf, 0), unknown by option.
  // Free cells that are no place (kSeen, the topology's map preparation) are free to a beam: the features describe
  // the space as the laser saw it; only the labels and nodes are kept off them.
  std::vector<std::pair<int, int>> spans;
  for (int pass = 0; pass < 2; ++pass) {
    for (FamilyState& st : state) std::fill(st.run.begin(), st.run.end(), map_border == BeamStop::kMaxRange ? st.max_run : 0);
    for (int t = 0; t < n_major; ++t) {
      const int k = pass == 0 ? t : n_major - 1 - t;
      const unsigned char* c = columns.ptr<unsigned char>(k);
      spans.clear();
      if (sparse) {
        // The union of this column's free spans and the previous column's, the latter one row wider each side.
        const std::pair<int, int>* cur = free_runs.runs.data() + free_runs.begin[static_cast<std::size_t>(k)];
        const std::pair<int, int>* cur_end = free_runs.runs.data() + free_runs.begin[static_cast<std::size_t>(k) + 1];
        const std::pair<int, int>* prev = cur_end;
        const std::pair<int, int>* prev_end = cur_end;
        if (t > 0) {
          const int kp = pass == 0 ? k - 1 : k + 1;
          prev = free_runs.runs.data() + free_runs.begin[static_cast<std::size_t>(kp)];
          prev_end = free_runs.runs.data() + free_runs.begin[static_cast<std::size_t>(kp) + 1];
        }
        int a = 0, b = -1;  // the pending merged span [a, b); none while b < a
        while (cur != cur_end || prev != prev_end) {
          std::pair<int, int> next;
          if (prev == prev_end || (cur != cur_end && cur->first <= prev->first - 1)) {
            next = *cur++;
          } else {
            next = {std::max(0, prev->first - 1), std::min(n_minor, prev->second + 1)};
            ++prev;
          }
          if (b >= a && next.first <= b) {
            b = std::max(b, next.second);
          } else {
            if (b > a) spans.emplace_back(a, b);
            a = next.first, b = next.second;
          }
        }
        if (b > a) spans.emplace_back(a, b);
      }
      for (std::size_t f = 0; f < families.size(); ++f) {
        FamilyState& st = state[f];
        const int max_run = st.max_run;
        // Beam-major output: one row per beam.
        std::uint16_t* out = by_beam.ptr<std::uint16_t>(pass == 0 ? families[f].beam_back : families[f].beam_ahead);
        // r[m]: the counter of the line through row m of column k (j = m - offset[k]).
        int* r = st.run.data() + (st.max_off - st.offset[static_cast<std::size_t>(k)]);
        const std::uint16_t* mm = st.mm.data();
        for (int s = samples.begin[static_cast<std::size_t>(k)]; s < samples.begin[static_cast<std::size_t>(k) + 1]; ++s) {
          const auto& [m, idx] = samples.items[static_cast<std::size_t>(s)];
          out[idx] = mm[r[m]];
        }
        if (sparse) {
          for (const std::pair<int, int>& span : spans)
            advanceFree(r + span.first, c + span.first, span.second - span.first, max_run);
        } else if (unknown_default) {
          for (int m = 0; m < n_minor; ++m) r[m] = (c[m] == kFree || c[m] == kSeen) ? std::min(r[m] + 1, max_run) : 0;
        } else if (unknown_cells == BeamStop::kMaxRange) {
          for (int m = 0; m < n_minor; ++m)
            r[m] = (c[m] == kFree || c[m] == kSeen) ? std::min(r[m] + 1, max_run) : c[m] == kUnknown ? max_run : 0;
        } else {
          for (int m = 0; m < n_minor; ++m) r[m] = c[m] != kOccupied ? std::min(r[m] + 1, max_run) : 0;
        }
      }
    }
  }
}

}  // namespace

int scanRowMargin(const OccupancyImage& occ, const ScanSimulationOptions& options) {
  // A family's run counter saturates after max_run = floor(max_range_mm / step_mm) + 2 steps, step_mm >= the
  // resolution: one more row than that.
  return static_cast<int>(std::floor(options.max_range / occ.resolution)) + 3;
}

cv::Mat simulateBeams(const OccupancyImage& occ, const std::vector<cv::Point>& samples_in,
                      const ScanSimulationOptions& options,
                      const std::function<void(std::size_t, std::size_t)>& progress) {
  options.validate();
  const int M = options.num_beams;
  if (samples_in.empty()) return cv::Mat(M, 0, CV_16U);
  int top = occ.rows(), bottom = -1;
  for (const cv::Point& p : samples_in) {
    if (p.x < 0 || p.y < 0 || p.x >= occ.cols() || p.y >= occ.rows() || !occ.isFree(p.y, p.x))
      throw std::invalid_argument("simulateBeams: sample is not a free cell of the map");
    top = std::min(top, p.y), bottom = std::max(bottom, p.y);
  }
  // The sweeps cover the samples' rows and `margin` rows on either side. A line's counter takes at most max_run
  // steps to forget where it started (each step adds one up to max_run, or sets a value that does not depend on
  // it), and a line entering the window through its top or bottom row makes at least one step per row it descends
  // (|slope| <= 1 along the columns; one step per row along the rows): at a sample it reads what it reads when
  // the lines are swept over the whole image. The steep families take their offsets from the image's row numbers.
  const int margin = scanRowMargin(occ, options);
  const int w0 = std::max(0, top - margin), w1 = std::min(occ.rows(), bottom + 1 + margin);
  const cv::Mat window = occ.cells.rowRange(w0, w1);
  std::vector<cv::Point> shifted;
  if (w0 > 0) {
    shifted.reserve(samples_in.size());
    for (const cv::Point& p : samples_in) shifted.emplace_back(p.x, p.y - w0);
  }
  const std::vector<cv::Point>& samples = w0 > 0 ? shifted : samples_in;
  const double max_mm = options.max_range * 1000.0;
  // Not initialised: every sample lies on one line of every family, and both sweeps of a family write its
  // two beams.
  cv::Mat by_beam(M, static_cast<int>(samples.size()), CV_16U);
  adviseHugePages(by_beam.data, by_beam.total() * by_beam.elemSize());
  // Shallow directions walk the image's columns, read as the rows of its transpose; steep ones walk the
  // transposed image's columns, i.e. the image's rows.
  cv::Mat cells_t;
  cv::transpose(window, cells_t);
  const ColumnSamples by_col = samplesByColumn(samples, window.cols, false);
  const ColumnSamples by_row = samplesByColumn(samples, window.rows, true);
  const bool sparse = options.unknown_cells == BeamStop::kObstacle && options.map_border == BeamStop::kObstacle;
  const RowRuns runs_t = sparse ? freeRunsOfRows(cells_t) : RowRuns{};
  const RowRuns runs = sparse ? freeRunsOfRows(window) : RowRuns{};
  // Directions k and k + M/2 share a family of lines; consecutive directions of the same kind (shallow: along
  // the image's columns, read as the rows of its transpose; steep: along the image's rows) are swept in groups of
  // up to kGroup (each column read once for the group). The groups do not change any range.
  constexpr std::size_t kGroup = 16;
  std::vector<std::vector<Family>> groups;
  std::vector<bool> group_steep;
  for (std::size_t k = 0; k < static_cast<std::size_t>(M / 2); ++k) {
    // Direction k (image coordinates: dc = cos, dr = -sin) and its opposite k + M/2.
    const double th = 2.0 * M_PI * static_cast<double>(k) / M;
    const double dc = std::cos(th), dr = -std::sin(th);
    const int kb = static_cast<int>(k), ko = static_cast<int>(k) + M / 2;
    Family f;
    const bool steep = std::abs(dc) < std::abs(dr);
    if (!steep) {
      // Travelling +1 column moves dr/dc rows; direction k points to +col iff dc > 0.
      f = {dr / dc, dc > 0 ? ko : kb, dc > 0 ? kb : ko};
    } else {
      // Steep: the same along the columns of the transposed image (+1 row moves dc/dr columns).
      f = {dc / dr, dr > 0 ? ko : kb, dr > 0 ? kb : ko};
    }
    if (groups.empty() || group_steep.back() != steep || groups.back().size() == kGroup) {
      groups.emplace_back();
      group_steep.push_back(steep);
    }
    groups.back().push_back(f);
  }
  const std::size_t n_dirs = groups.size();
  std::atomic<std::size_t> next{0}, done{0};
  auto process = [&](std::size_t g) {
    if (!group_steep[g])
      sweepFamilies(cells_t, by_col, runs_t, occ.resolution, groups[g], 0, max_mm, options.unknown_cells,
                    options.map_border, by_beam);
    else
      sweepFamilies(window, by_row, runs, occ.resolution, groups[g], w0, max_mm, options.unknown_cells,
                    options.map_border, by_beam);
  };
  auto worker = [&](bool report) {
    for (std::size_t k; (k = next.fetch_add(1)) < n_dirs;) {
      process(k);
      const std::size_t d = done.fetch_add(1) + 1;
      if (report && progress) progress(d, n_dirs);
    }
  };
  const int nt = std::max(1, std::min(options.threads, static_cast<int>(n_dirs)));
  std::vector<std::thread> pool;
  for (int t = 1; t < nt; ++t) pool.emplace_back(worker, false);
  worker(true);  // the calling thread works too and reports progress
  for (auto& t : pool) t.join();
  if (progress) progress(n_dirs, n_dirs);
  return by_beam;
}

SimulatedScans simulateScans(const OccupancyImage& occ, const std::vector<cv::Point>& samples,
                             const ScanSimulationOptions& options,
                             const std::function<void(std::size_t, std::size_t)>& progress) {
  options.validate();
  SimulatedScans out;
  out.num_beams = options.num_beams;
  const int M = options.num_beams;
  if (samples.empty()) return out;
  for (const cv::Point& p : samples)
    if (p.x < 0 || p.y < 0 || p.x >= occ.cols() || p.y >= occ.rows() || !occ.isFree(p.y, p.x))
      throw std::invalid_argument("simulateScans: sample is not a free cell of the map");
  cv::Mat by_beam = simulateBeams(occ, samples, options, progress);
  out.ranges_mm.resize(samples.size() * static_cast<std::size_t>(M));
  cv::Mat by_sample(static_cast<int>(samples.size()), M, CV_16U, out.ranges_mm.data());
  // Sample-major for the feature extraction, each thread transposing its own range of samples.
  const int n_samples = static_cast<int>(samples.size());
  const int nt = std::max(1, std::min(options.threads, M / 2));
  auto transposePart = [&](int t) {
    const int a = n_samples * t / nt, b = n_samples * (t + 1) / nt;
    if (b <= a) return;
    cv::Mat dst = by_sample.rowRange(a, b);
    cv::transpose(by_beam.colRange(a, b), dst);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < nt; ++t) pool.emplace_back(transposePart, t);
  transposePart(0);
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace gridtopo::places
