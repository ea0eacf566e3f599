#include "gridtopo/experiment/plots.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "gridtopo/core/output_set.h"
#include "gridtopo/experiment/run_scoring.h"
#include "gridtopo/experiment/run_statistics.h"
#include "gridtopo/experiment/subprocess.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

struct Point {
  double particles;
  Spread error, wall;
  double success_rate;  // NaN: no run with error figures
  std::size_t runs;
};
struct Series {
  std::string title;
  std::vector<Point> points;
};

double particlesOf(const RunRecord& r) {
  for (const auto& [k, v] : r.options)
    if (k == "particles") return std::atof(v.c_str());
  return NAN;
}

std::vector<Series> seriesOf(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  const auto keys = keysBut(plan.varied_keys, {"seed", "particles"});
  std::vector<Series> out;
  for (const auto& g : groupRuns(records, keys)) {
    Series s;
    for (const auto& [k, v] : g.key) s.title += (s.title.empty() ? "" : " ") + v;
    if (s.title.empty()) s.title = plan.spec.name;
    std::map<double, std::vector<const RunRecord*>> by_p;
    for (const RunRecord* r : g.runs) by_p[particlesOf(*r)].push_back(r);
    for (const auto& [p, runs] : by_p) {
      std::vector<double> err, wall;
      std::size_t scored = 0, succ = 0;
      for (const RunRecord* r : runs) {
        const int su = successOf(plan.spec, *r);
        if (su >= 0) ++scored, succ += su == 1;
        if (r->ok()) wall.push_back(r->wall_s);
        if (r->hasErrors()) err.push_back(r->trans_mean);
      }
      s.points.push_back({p, Spread::of(err), Spread::of(wall),
                          scored ? static_cast<double>(succ) / static_cast<double>(scored) : NAN, runs.size()});
    }
    out.push_back(s);
  }
  return out;
}

std::string num(double v) { return std::isfinite(v) ? io::formatDouble(v) : std::string("NaN"); }

std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream in(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(in, dir, ':')) {
    const fs::path p = fs::path(dir.empty() ? "." : dir) / name;
    if (::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p)) return p.string();
  }
  return "";
}

std::string particlesTable(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  std::ostringstream o;
  o << "# Experiment " << plan.spec.name << ": per series (one block each, gnuplot 'index i'), per particle count:\n"
    << "# particles, translational error mean over the seeds' runs (m), its std, success rate (0..1), wall time "
       "mean (s), its std, runs\n";
  bool first = true;
  for (const auto& s : seriesOf(plan, records)) {
    o << (first ? "" : "\n\n") << "# " << s.title << "\n";
    first = false;
    for (const auto& p : s.points)
      o << num(p.particles) << ' ' << num(p.error.mean) << ' ' << num(p.error.count ? p.error.std : NAN) << ' '
        << num(p.success_rate) << ' ' << num(p.wall.mean) << ' ' << num(p.wall.count ? p.wall.std : NAN) << ' '
        << p.runs << "\n";
  }
  return o.str();
}

std::string plotScript(const ExperimentPlan& plan, const std::vector<RunRecord>& records, const std::string& which) {
  const auto series = seriesOf(plan, records);
  std::vector<double> xs;
  for (const auto& s : series)
    for (const auto& p : s.points)
      if (std::isfinite(p.particles)) xs.push_back(p.particles);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  const std::string name = which == "error" ? "error_vs_particles" : which == "success" ? "success_vs_particles"
                                                                                         : "time_vs_particles";
  std::ostringstream o;
  o << "# gridtopo-experiment plot of experiment '" << plan.spec.name << "'. Edit and run `gnuplot " << name
    << ".gp` in this folder to redraw " << name << ".png and " << name << ".svg.\n";
  o << "set encoding utf8\nset grid\nset key outside right top noenhanced\n";
  o << "set offsets graph 0.05, graph 0.05, graph 0.05, graph 0.05\n";
  if (xs.size() > 1 && xs.front() > 0) o << "set logscale x 2\n";
  o << "set xtics (";
  for (std::size_t i = 0; i < xs.size(); ++i) o << (i ? ", " : "") << num(xs[i]);
  o << ")\nset xlabel \"particles\"\n";
  std::string using_, style;
  if (which == "error") {
    o << "set title " << quoted("Translational error vs particles (" + plan.spec.name + ")") << "\n";
    o << "set ylabel \"translational error (m): mean over seeds, bars ±1 std\"\nset yrange [0:*]\n";
    using_ = "1:2:3";
    style = "yerrorlines";
  } else if (which == "success") {
    o << "set title " << quoted("Success rate vs particles (" + plan.spec.name + ")") << "\n";
    const bool metres = plan.spec.success_metric == SuccessMetric::TransMean ||
                        plan.spec.success_metric == SuccessMetric::TransMax;
    o << "set ylabel " << quoted(std::string("success rate over seeds (") + toString(plan.spec.success_metric) +
                                 " <= " + num(plan.spec.success_threshold) + (metres ? " m)" : " deg)"))
      << "\nset yrange [0:1.05]\n";
    using_ = "1:4";
    style = "linespoints";
  } else {
    o << "set title " << quoted("Wall time per run vs particles (" + plan.spec.name + ")") << "\n";
    o << "set ylabel \"wall time per run (s): mean over seeds, bars ±1 std\"\nset yrange [0:*]\n";
    using_ = "1:5:6";
    style = "yerrorlines";
  }
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < series.size(); ++i) {
    bool has = false;
    for (const auto& p : series[i].points)
      has |= std::isfinite(which == "error" ? p.error.mean : which == "success" ? p.success_rate : p.wall.mean);
    if (!has) continue;
    parts.push_back("'by_particles.dat' index " + std::to_string(i) + " using " + using_ + " with " + style +
                    " pointtype 7 title " + quoted(series[i].title));
  }
  if (parts.empty()) return "";
  o << "set terminal pngcairo size 960,600 font \",11\" noenhanced\nset output '" << name << ".png'\nplot ";
  for (std::size_t i = 0; i < parts.size(); ++i) o << (i ? ", \\\n     " : "") << parts[i];
  o << "\nset terminal svg size 960,600 font \"sans,11\" noenhanced\nset output '" << name << ".svg'\nreplot\nunset output\n";
  return o.str();
}

std::string neffPlots(const ExperimentPlan& plan, const std::vector<RunRecord>& records,
                      std::vector<std::pair<std::string, std::string>>& files) {
  std::string index;
  for (const auto& g : groupRuns(records, keysBut(plan.varied_keys, {"seed"}))) {
    std::string name, title;
    for (const auto& [k, v] : g.key) {
      name += (name.empty() ? "" : "_") + (k == "dataset" || k == "proposal" ? v : k + "-" + v);
      title += (title.empty() ? "" : ", ") + k + " " + v;
    }
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    if (name.empty()) name = "all";
    std::ostringstream dat, parts;
    std::size_t blocks = 0;
    for (const RunRecord* r : g.runs) {
      if (!r->ok()) continue;
      std::ifstream f(fs::path(r->dir) / "out" / "stats.txt");
      if (!f) continue;
      std::ostringstream text;
      text << f.rdbuf();
      const StepSummary steps = summarizeSteps(text.str(), (fs::path(r->dir) / "out" / "stats.txt").string());
      const double n = particlesOf(*r);
      if (steps.neff.empty() || !(n > 0)) continue;
      dat << (blocks ? "\n\n" : "") << "# " << r->label << "\n";
      for (std::size_t i = 0; i < steps.neff.size(); ++i) dat << i << ' ' << num(steps.neff[i] / n) << "\n";
      parts << (blocks ? ", \\\n     " : "") << "'" << name << ".dat' index " << blocks << " using 1:2 with lines title "
            << quoted(r->label);
      ++blocks;
    }
    if (!blocks) continue;
    std::ostringstream gp;
    gp << "# gridtopo-experiment plot of experiment '" << plan.spec.name << "': N_eff over the processed steps of each run"
       << " of one group. Edit and run `gnuplot " << name << ".gp` in this folder to redraw it.\n"
       << "set encoding utf8\nset grid\nset key outside right top noenhanced\n"
       << "set title " << quoted("N_eff / particles per processed scan: " + title) << "\n"
       << "set xlabel \"processed scan (filter step)\"\nset ylabel \"N_eff / particles\"\nset yrange [0:1.05]\n"
       << "set terminal pngcairo size 960,600 font \",11\" noenhanced\nset output '" << name << ".png'\nplot "
       << parts.str() << "\nset terminal svg size 960,600 font \"sans,11\" noenhanced\nset output '" << name
       << ".svg'\nreplot\nunset output\n";
    files.emplace_back("neff/" + name + ".dat", dat.str());
    files.emplace_back("neff/" + name + ".gp", gp.str());
    index += name + "\n";
  }
  return index;
}

PlotFiles drawPlots(const ExperimentPlan& plan, const std::vector<RunRecord>& records) {
  PlotFiles files;
  if (plan.spec.plots.empty()) return files;
  const fs::path dir = fs::path(plan.output) / "plots";
  std::vector<std::pair<std::string, std::string>> written;  // path under plots/, text
  std::vector<std::string> scripts;                          // .gp paths under plots/
  bool by_particles = false;
  for (const auto& which : plan.spec.plots) {
    if (which == "neff") {
      std::vector<std::pair<std::string, std::string>> neff;
      if (neffPlots(plan, records, neff).empty()) files.notes.push_back("no neff plot: no run has a stats.txt");
      for (const auto& f : neff) {
        written.push_back(f);
        if (f.first.size() > 3 && f.first.compare(f.first.size() - 3, 3, ".gp") == 0) scripts.push_back(f.first);
      }
      continue;
    }
    const std::string text = plotScript(plan, records, which);
    if (text.empty()) {
      files.notes.push_back("no " + which + " plot: no run has data for it");
      continue;
    }
    const std::string name = which == "error" ? "error_vs_particles" : which == "success" ? "success_vs_particles"
                                                                                           : "time_vs_particles";
    written.emplace_back(name + ".gp", text);
    scripts.push_back(name + ".gp");
    by_particles = true;
  }
  if (by_particles) written.emplace_back("by_particles.dat", particlesTable(plan, records));
  if (scripts.empty()) return files;
  {
    OutputSet out;
    for (const auto& [rel, text] : written)
      out.write((dir / rel).string(), [&](const std::string& p) { writeTextFileAtomically(p, text); });
    out.commit();
  }
  for (const auto& rel : scripts) files.scripts.push_back((dir / rel).string());
  const std::string gnuplot = findOnPath("gnuplot");
  if (gnuplot.empty()) {
    files.notes.push_back("gnuplot not found: the .gp scripts are written, no pictures (apt-get install gnuplot-nox)");
    return files;
  }
  fs::remove(dir / "gnuplot.log");
  for (const auto& rel : scripts) {
    const fs::path gp = dir / rel;
    const fs::path base = gp.parent_path() / gp.stem();
    for (const char* ext : {".png", ".svg"}) fs::remove(base.string() + ext);
    const auto r = runProcess({gnuplot, gp.filename().string()}, (dir / "gnuplot.log").string(),
                              gp.parent_path().string());
    bool made = r.ok();
    for (const char* ext : {".png", ".svg"}) {
      const std::string pic = base.string() + ext;
      if (fs::is_regular_file(pic) && fs::file_size(pic) > 0) files.pictures.push_back(pic);
      else made = false;
    }
    if (!made) files.notes.push_back("gnuplot failed on " + gp.string() + ", see " + (dir / "gnuplot.log").string());
  }
  if (files.notes.empty()) fs::remove(dir / "gnuplot.log");
  return files;
}

}  // namespace gridtopo::experiment
