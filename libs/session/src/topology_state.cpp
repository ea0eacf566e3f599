#include "gridtopo/session/topology_state.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/places/features.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/regions.h"
#include "gridtopo/topology/topology_outputs.h"

namespace gridtopo::session {

namespace fs = std::filesystem;

const cv::Mat& TopologyData::labels(LabelStage s) const {
  static const cv::Mat none;
  switch (s) {
    case LabelStage::Classified: return has_labelling ? labelling.labels_initial : none;
    case LabelStage::Relaxed: return has_labelling ? labelling.labels : none;
    case LabelStage::Corrected: return topo.labels;
  }
  return none;
}

TopologyData computeTopology(const MapLayer& map, std::shared_ptr<const places::PlacesModel> model,
                             const topology::TopologyOptions& options,
                             const std::function<void(const std::string&, std::size_t, std::size_t)>& progress) {
  if (!model) throw InputError("<model>", "open a place model (gridtopo-train output) first");
  if (map.empty()) throw InputError("<map>", "open a map first");
  const auto t0 = std::chrono::steady_clock::now();
  TopologyData t;
  t.map = map;
  t.model = model;
  // The one topology run, keeping the scans and the features for the cell inspector.
  topology::MapTopology run = topology::topologyOfMap(map.image(), *model, options, progress, true);
  t.occ = std::move(run.occ);
  t.labelling = std::move(run.labelling);
  t.topo = std::move(run.topo);
  t.scans = std::move(t.labelling.scans);
  t.features = std::move(t.labelling.features);
  t.has_labelling = true;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress("done", 1, 1);
  return t;
}

topology::TopologicalGraph graphFromGraphML(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the file");
  topology::TopologicalGraph g;
  const std::regex node_re(R"re(<node id="n(-?\d+)">)re"),
      edge_re(R"re(<edge source="n(-?\d+)" target="n(-?\d+)">)re"), data_re(R"re(<data key="(\w+)">([^<]*)</data>)re");
  std::string line;
  std::size_t ln = 0;
  bool graphml = false;
  while (std::getline(in, line)) {
    ++ln;
    if (line.find("<graphml") != std::string::npos) graphml = true;
    std::smatch m;
    std::map<std::string, std::string> data;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), data_re); it != std::sregex_iterator(); ++it)
      data[(*it)[1]] = (*it)[2];
    auto num = [&](const std::string& k) {
      const auto f = data.find(k);
      if (f == data.end()) throw InputError(path, ln, k, "missing");
      try {
        std::size_t used = 0;
        const double v = std::stod(f->second, &used);
        if (used != f->second.size() || !std::isfinite(v)) throw std::invalid_argument("x");
        return v;
      } catch (const std::exception&) {
        throw InputError(path, ln, k, "'" + f->second + "' is not a number");
      }
    };
    if (std::regex_search(line, m, node_re)) {
      topology::GraphNode n;
      n.id = std::stoi(m[1]);
      const std::string l = data.count("label") ? data["label"] : "";
      n.label = l == "room" ? 0 : l == "corridor" ? 1 : l == "doorway" ? 2 : -1;
      if (n.label < 0) throw InputError(path, ln, "label", "unknown label '" + l + "'");
      n.area_m2 = num("area_m2");
      n.cells = static_cast<int>(num("cells"));
      n.centroid_m = {num("x_m"), num("y_m")};
      n.centroid_px = {num("col"), num("row")};
      n.anchor_px = data.count("anchor_col") && data.count("anchor_row")
                        ? cv::Point(static_cast<int>(num("anchor_col")), static_cast<int>(num("anchor_row")))
                        : cv::Point(cvRound(n.centroid_px.x), cvRound(n.centroid_px.y));
      n.bbox_px = cv::Rect(static_cast<int>(num("bbox_x")), static_cast<int>(num("bbox_y")),
                           static_cast<int>(num("bbox_w")), static_cast<int>(num("bbox_h")));
      g.nodes.push_back(n);
    } else if (std::regex_search(line, m, edge_re)) {
      topology::GraphEdge e;
      e.a = std::stoi(m[1]);
      e.b = std::stoi(m[2]);
      e.border_cells = data.count("border_cells") ? static_cast<int>(num("border_cells")) : 0;
      e.via_doorway = data.count("via_doorway") && data["via_doorway"] == "true";
      if (data.count("path_px")) {  // the drawn route: "col,row col,row ..."
        std::istringstream points(data["path_px"]);
        std::string point;
        while (points >> point) {
          int x = 0, y = 0;
          char comma = 0, extra = 0;
          std::istringstream one(point);
          if (!(one >> x >> comma >> y) || comma != ',' || (one >> extra))
            throw InputError(path, ln, "path_px", "'" + point + "' is not col,row");
          e.path_px.emplace_back(x, y);
        }
      }
      g.edges.push_back(e);
    }
  }
  if (!graphml) throw InputError(path, 1, "graphml", "not a GraphML file");
  for (const auto& e : g.edges)
    if (!g.node(e.a) || !g.node(e.b))
      throw InputError(path, 0, "edge", "edge " + std::to_string(e.a) + "-" + std::to_string(e.b) +
                                            " refers to a missing node");
  return g;
}

TopologyData loadTopologyOutput(const std::string& path, const MapLayer& map, const topology::TopologyOptions& options) {
  TopologyData t;
  t.map = map;
  const std::string ext = fs::path(path).extension().string();
  t.topo.graph = ext == ".graphml" ? graphFromGraphML(path) : topology::graphFromJson(path);
  const fs::path labels = fs::path(path).parent_path() / "labels.png";
  if (fs::is_regular_file(labels)) {
    if (map.empty()) throw InputError(path, std::string("open the map this topology was computed on first (labels.png is ") +
                                                "pixel-aligned with it)");
    cv::Mat codes = cv::imread(labels.string(), cv::IMREAD_GRAYSCALE);
    if (codes.empty()) throw InputError(labels.string(), "cannot read the image");
    if (codes.size() != map.grey.size())
      throw InputError(labels.string(), "label image is " + std::to_string(codes.cols) + "x" +
                                            std::to_string(codes.rows) + " but the open map is " +
                                            std::to_string(map.cols()) + "x" + std::to_string(map.rows()));
    t.topo.labels = places::labelsFromCodes(codes);
    t.topo.regions = topology::extractRegions(t.topo.labels, map.resolution);
  } else if (!map.empty() && (t.topo.graph.rows != map.rows() || t.topo.graph.cols != map.cols())) {
    // Graph only: it is drawn in the frame of the open map, which must be the same size.
    throw InputError(path, 0, "rows/cols",
                     "graph is for a " + std::to_string(t.topo.graph.cols) + "x" + std::to_string(t.topo.graph.rows) +
                         " map but the open map is " + std::to_string(map.cols()) + "x" + std::to_string(map.rows()));
  }
  if (!map.empty())
    t.occ = topology::occupancyForTopology(map.image(), options);
  return t;
}

namespace {
std::string featureUnit(const std::string& name) {
  if (name == "area") return "m^2";
  if (name.rfind("gaps_", 0) == 0) return "count";
  for (const char* m : {"diff", "beam", "chord", "perimeter", "area_perimeter", "centroid_dist", "ellipse_major",
                        "ellipse_minor", "centroid_offset"})
    if (name.find(m) != std::string::npos && name != "chord_centering") return "m";
  return "-";
}
std::string fmt(double v, int prec = 3) {
  std::ostringstream o;
  o.precision(prec);
  o << std::fixed << v;
  return o.str();
}
}  // namespace

cv::Point2d pixelWorld(const TopologyData& t, const cv::Point2d& px) {
  // Pixels of the map image (row 0 top); cell (c, r) centre = cellCentre(r, c).
  return {t.map.origin_x + (px.x + 0.5) * t.map.resolution, t.map.origin_y + (t.map.rows() - px.y - 0.5) * t.map.resolution};
}

cv::Point2d nodeAnchorWorld(const TopologyData& t, const topology::GraphNode& n) {
  return pixelWorld(t, cv::Point2d(n.anchor_px));
}

cv::Point2d nodeWorld(const TopologyData& t, const topology::GraphNode& n) { return pixelWorld(t, n.centroid_px); }

CellInspection inspectCell(const TopologyData& t, int row, int col) {
  if (row < 0 || col < 0 || row >= t.map.rows() || col >= t.map.cols())
    throw std::out_of_range("cell outside the map");
  CellInspection ci;
  ci.row = row, ci.col = col;
  const cv::Point2d w = t.map.cellCentre(row, col);
  ci.x = w.x, ci.y = w.y;
  ci.occupancy = t.map.occupancy(row, col);
  ci.free = !t.occ.cells.empty() && t.occ.isFree(row, col);
  auto label = [&](const cv::Mat& m) { return m.empty() || m.at<unsigned char>(row, col) > 2 ? -1 : m.at<unsigned char>(row, col); };
  ci.label_corrected = label(t.topo.labels);
  if (!t.topo.regions.ids.empty()) ci.region = t.topo.regions.ids.at<int>(row, col);
  if (!t.has_labelling || !ci.free) return ci;
  ci.label_classified = label(t.labelling.labels_initial);
  ci.label_relaxed = label(t.labelling.labels);
  const auto& lat = t.labelling.lattice;
  ci.sample = lat.sampleOfPixel(row, col);
  if (ci.sample < 0) return ci;
  ci.has_sample = true;
  const cv::Point block = lat.blocks[static_cast<std::size_t>(ci.sample)];
  ci.sample_cell = lat.samples[static_cast<std::size_t>(ci.sample)];
  const cv::Vec3f p0 = t.labelling.probs_initial.at<cv::Vec3f>(block), p1 = t.labelling.probs.at<cv::Vec3f>(block);
  for (int k = 0; k < 3; ++k) ci.p_classified[k] = p0[k], ci.p_relaxed[k] = p1[k];
  ci.feature_descriptions = places::featureDescriptions();
  ci.feature_names = places::featureNames();
  const float* f = t.features.ptr<float>(ci.sample);
  // The base features (the capped-range and context copies of a model are not listed).
  ci.features.assign(f, f + std::min(static_cast<std::size_t>(t.features.cols), places::numFeatures()));
  const int M = t.scans.num_beams;
  const std::uint16_t* r = t.scans.scan(static_cast<std::size_t>(ci.sample));
  const cv::Point2d o = t.map.cellCentre(ci.sample_cell.y, ci.sample_cell.x);
  for (int k = 0; k < M; ++k) {
    const double a = 2.0 * M_PI * k / M, d = r[k] / 1000.0;
    ci.scan_world.emplace_back(o.x + d * std::cos(a), o.y + d * std::sin(a));
  }
  return ci;
}

std::string CellInspection::text() const {
  std::ostringstream o;
  o << "cell (col " << col << ", row " << row << ")  x = " << fmt(x) << " m, y = " << fmt(y) << " m\n";
  o << "occupancy p = " << fmt(occupancy, 2) << (free ? " (free)" : " (not free)") << "\n";
  auto name = [](int l) { return places::labelName(l); };
  if (label_corrected >= 0 || label_relaxed >= 0)
    o << "label: " << name(label_corrected) << " (classified " << name(label_classified) << ", relaxed "
      << name(label_relaxed) << ", after region correction " << name(label_corrected) << ")\n";
  if (region > 0) o << "region " << region << "\n";
  if (!has_sample) return o.str();
  o << "classified at sample cell (col " << sample_cell.x << ", row " << sample_cell.y << ")\n";
  o << "P(room, corridor, doorway) before relaxation: " << fmt(p_classified[0]) << " " << fmt(p_classified[1]) << " "
    << fmt(p_classified[2]) << "\n";
  o << "P(room, corridor, doorway) after relaxation:  " << fmt(p_relaxed[0]) << " " << fmt(p_relaxed[1]) << " "
    << fmt(p_relaxed[2]) << "\n";
  o << "features (" << features.size() << "):\n";
  for (std::size_t i = 0; i < features.size() && i < feature_names.size(); ++i)
    o << "  " << feature_names[i] << " = " << features[i] << " [" << featureUnit(feature_names[i]) << "]  "
      << feature_descriptions[i].substr(feature_descriptions[i].find(':') + 1) << "\n";
  return o.str();
}

std::optional<NodeInspection> inspectNodeAt(const TopologyData& t, double x, double y, double radius_m) {
  const topology::GraphNode* best = nullptr;
  double bd = radius_m;
  for (const auto& n : t.topo.graph.nodes) {
    const cv::Point2d w = nodeWorld(t, n);
    const double d = std::hypot(w.x - x, w.y - y);
    if (d <= bd) bd = d, best = &n;
  }
  if (!best) return std::nullopt;
  NodeInspection ni;
  ni.id = best->id, ni.label = best->label, ni.cells = best->cells, ni.area_m2 = best->area_m2;
  ni.centroid_world = nodeWorld(t, *best);
  for (const auto& e : t.topo.graph.edges) {
    if (e.a == best->id) ni.neighbours.push_back(e.b);
    if (e.b == best->id) ni.neighbours.push_back(e.a);
  }
  return ni;
}

std::string NodeInspection::text() const {
  std::ostringstream o;
  o << "region " << id << ": " << places::labelName(label) << "\n"
    << "area " << fmt(area_m2, 2) << " m^2 (" << cells << " cells)\n"
    << "centroid x = " << fmt(centroid_world.x, 2) << " m, y = " << fmt(centroid_world.y, 2) << " m\n"
    << "neighbours:";
  for (int n : neighbours) o << " " << n;
  o << "\n";
  return o.str();
}

void saveTopologyOutputs(const TopologyData& t, const std::string& dir, const topology::TopologyOptions& options) {
  if (t.topo.labels.empty()) throw std::runtime_error("no topology with labels to save");
  // The files of gridtopo-topology; options.ini holds the options as a loadable INI (its -c, or a RUN.ini's
  // option sections).
  topology::writeTopologyOutputs(dir, t.occ, t.topo, t.has_labelling ? t.labelling.labels : cv::Mat(),
                                 options.overlay_scale, topology::topologyOptionsIni(options));
}

}  // namespace gridtopo::session
