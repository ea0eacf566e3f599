#include "gridtopo/topology/export.h"

#include <algorithm>
#include <thread>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"

namespace gridtopo::topology {

namespace {
std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}
// "x0,y0 x1,y1 ..." for GraphML, [[x0, y0], [x1, y1], ...] for JSON.
std::string pathText(const std::vector<cv::Point>& path, bool json) {
  std::ostringstream o;
  if (json) o << "[";
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (json) o << (i ? ", " : "") << "[" << path[i].x << ", " << path[i].y << "]";
    else o << (i ? " " : "") << path[i].x << "," << path[i].y;
  }
  if (json) o << "]";
  return o.str();
}
}  // namespace

std::string toGraphML(const TopologicalGraph& g) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<graphml xmlns=\"http://graphml.graphdrawing.org/xmlns\">\n";
  const char* keys[][3] = {{"label", "node", "string"},   {"area_m2", "node", "double"},
                           {"cells", "node", "int"},      {"x_m", "node", "double"},
                           {"y_m", "node", "double"},     {"col", "node", "double"},
                           {"row", "node", "double"},     {"bbox_x", "node", "int"},
                           {"bbox_y", "node", "int"},     {"bbox_w", "node", "int"},
                           {"bbox_h", "node", "int"},     {"anchor_col", "node", "int"},
                           {"anchor_row", "node", "int"}, {"border_cells", "edge", "int"},
                           {"via_doorway", "edge", "boolean"},
                           {"path_px", "edge", "string"}};
  for (const auto& k : keys)
    o << "  <key id=\"" << k[0] << "\" for=\"" << k[1] << "\" attr.name=\"" << k[0] << "\" attr.type=\"" << k[2]
      << "\"/>\n";
  o << "  <graph id=\"topology\" edgedefault=\"undirected\">\n";
  for (const auto& n : g.nodes) {
    o << "    <node id=\"n" << n.id << "\">"
      << "<data key=\"label\">" << places::labelName(n.label) << "</data>"
      << "<data key=\"area_m2\">" << num(n.area_m2) << "</data>"
      << "<data key=\"cells\">" << n.cells << "</data>"
      << "<data key=\"x_m\">" << num(n.centroid_m.x) << "</data>"
      << "<data key=\"y_m\">" << num(n.centroid_m.y) << "</data>"
      << "<data key=\"col\">" << num(n.centroid_px.x) << "</data>"
      << "<data key=\"row\">" << num(n.centroid_px.y) << "</data>"
      << "<data key=\"bbox_x\">" << n.bbox_px.x << "</data>"
      << "<data key=\"bbox_y\">" << n.bbox_px.y << "</data>"
      << "<data key=\"bbox_w\">" << n.bbox_px.width << "</data>"
      << "<data key=\"bbox_h\">" << n.bbox_px.height << "</data>"
      << "<data key=\"anchor_col\">" << n.anchor_px.x << "</data>"
      << "<data key=\"anchor_row\">" << n.anchor_px.y << "</data></node>\n";
  }
  for (const auto& e : g.edges)
    o << "    <edge source=\"n" << e.a << "\" target=\"n" << e.b << "\">"
      << "<data key=\"border_cells\">" << e.border_cells << "</data>"
      << "<data key=\"via_doorway\">" << (e.via_doorway ? "true" : "false") << "</data>"
      << "<data key=\"path_px\">" << pathText(e.path_px, false) << "</data></edge>\n";
  o << "  </graph>\n</graphml>\n";
  return o.str();
}

std::string toJson(const TopologicalGraph& g) {
  std::ostringstream o;
  o << "{\n  \"format\": \"gridtopo-topology\",\n  \"resolution\": " << num(g.resolution) << ",\n  \"rows\": " << g.rows
    << ",\n  \"cols\": " << g.cols << ",\n  \"nodes\": [";
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const auto& n = g.nodes[i];
    o << (i ? "," : "") << "\n    {\"id\": " << n.id << ", \"label\": \"" << places::labelName(n.label)
      << "\", \"area_m2\": " << num(n.area_m2) << ", \"cells\": " << n.cells << ", \"centroid_m\": [" << num(n.centroid_m.x)
      << ", " << num(n.centroid_m.y) << "], \"centroid_px\": [" << num(n.centroid_px.x) << ", " << num(n.centroid_px.y)
      << "], \"bbox_px\": [" << n.bbox_px.x << ", " << n.bbox_px.y << ", " << n.bbox_px.width << ", "
      << n.bbox_px.height << "], \"anchor_px\": [" << n.anchor_px.x << ", " << n.anchor_px.y << "]}";
  }
  o << "\n  ],\n  \"edges\": [";
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    const auto& e = g.edges[i];
    o << (i ? "," : "") << "\n    {\"a\": " << e.a << ", \"b\": " << e.b << ", \"border_cells\": " << e.border_cells
      << ", \"via_doorway\": " << (e.via_doorway ? 1 : 0) << ", \"contact_px\": [" << num(e.contact_px.x) << ", "
      << num(e.contact_px.y) << "], \"path_px\": " << pathText(e.path_px, true) << "}";
  }
  o << "\n  ]\n}\n";
  return o.str();
}

std::string toDot(const TopologicalGraph& g) {
  static const char* colour[] = {"lightblue", "palegreen", "salmon"};
  std::ostringstream o;
  o << "graph topology {\n  node [style=filled];\n";
  for (const auto& n : g.nodes)
    o << "  n" << n.id << " [label=\"" << n.id << " " << places::labelName(n.label) << "\\n" << std::fixed
      << std::setprecision(1) << n.area_m2 << " m2\", fillcolor=" << colour[n.label] << ", pos=\""
      << std::setprecision(2) << n.centroid_m.x << "," << n.centroid_m.y << "!\"];\n";
  for (const auto& e : g.edges)
    o << "  n" << e.a << " -- n" << e.b << (e.via_doorway ? "" : " [style=dashed]") << ";\n";
  o << "}\n";
  return o.str();
}

TopologicalGraph graphFromJson(const std::string& path) {
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ | cv::FileStorage::FORMAT_JSON);
  } catch (const cv::Exception&) {
    throw InputError(path, "not valid JSON");
  }
  if (!fs.isOpened() || static_cast<std::string>(fs["format"]) != "gridtopo-topology")
    throw InputError(path, 0, "format", "not a gridtopo topology JSON file");
  TopologicalGraph g;
  g.resolution = static_cast<double>(fs["resolution"]);
  g.rows = static_cast<int>(fs["rows"]);
  g.cols = static_cast<int>(fs["cols"]);
  for (const auto& n : fs["nodes"]) {
    GraphNode gn;
    gn.id = static_cast<int>(n["id"]);
    const std::string l = static_cast<std::string>(n["label"]);
    gn.label = l == "room" ? 0 : l == "corridor" ? 1 : l == "doorway" ? 2 : -1;
    if (gn.label < 0) throw InputError(path, 0, "label", "unknown label '" + l + "'");
    gn.area_m2 = static_cast<double>(n["area_m2"]);
    gn.cells = static_cast<int>(n["cells"]);
    gn.centroid_m = cv::Point2d(static_cast<double>(n["centroid_m"][0]), static_cast<double>(n["centroid_m"][1]));
    gn.centroid_px = cv::Point2d(static_cast<double>(n["centroid_px"][0]), static_cast<double>(n["centroid_px"][1]));
    gn.bbox_px = cv::Rect(static_cast<int>(n["bbox_px"][0]), static_cast<int>(n["bbox_px"][1]),
                          static_cast<int>(n["bbox_px"][2]), static_cast<int>(n["bbox_px"][3]));
    // Files written before anchors were exported: the centroid stands in.
    gn.anchor_px = n["anchor_px"].empty()
                       ? cv::Point(cvRound(gn.centroid_px.x), cvRound(gn.centroid_px.y))
                       : cv::Point(static_cast<int>(n["anchor_px"][0]), static_cast<int>(n["anchor_px"][1]));
    // The anchor in metres, with the map origin the centroid's two coordinates imply.
    const cv::Point2d origin = gn.centroid_m - cv::Point2d((gn.centroid_px.x + 0.5) * g.resolution,
                                                           (g.rows - gn.centroid_px.y - 0.5) * g.resolution);
    gn.anchor_m = origin + cv::Point2d((gn.anchor_px.x + 0.5) * g.resolution, (g.rows - gn.anchor_px.y - 0.5) * g.resolution);
    g.nodes.push_back(gn);
  }
  for (const auto& e : fs["edges"]) {
    GraphEdge ge;
    ge.a = static_cast<int>(e["a"]);
    ge.b = static_cast<int>(e["b"]);
    ge.border_cells = static_cast<int>(e["border_cells"]);
    ge.via_doorway = static_cast<int>(e["via_doorway"]) != 0;
    ge.contact_px = cv::Point2d(static_cast<double>(e["contact_px"][0]), static_cast<double>(e["contact_px"][1]));
    for (const auto& q : e["path_px"]) ge.path_px.emplace_back(static_cast<int>(q[0]), static_cast<int>(q[1]));
    g.edges.push_back(ge);
  }
  return g;
}

int overlayScaleFor(cv::Size map, int requested) {
  int scale = std::max(1, requested);
  const auto fits = [&](int s) {
    const long long w = static_cast<long long>(map.width) * s, h = static_cast<long long>(map.height) * s;
    return w <= kOverlayMaxSide && h <= kOverlayMaxSide && w * h <= kOverlayMaxPixels;
  };
  while (scale > 1 && !fits(scale)) --scale;
  return scale;
}

cv::Mat regionBorders(const cv::Mat& ids) {
  CV_Assert(ids.type() == CV_32S);
  cv::Mat borders(ids.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < ids.rows; ++y) {
    const int* row = ids.ptr<int>(y);
    const int* below = y + 1 < ids.rows ? ids.ptr<int>(y + 1) : nullptr;
    unsigned char* out = borders.ptr<unsigned char>(y);
    for (int x = 0; x < ids.cols; ++x) {
      const int id = row[x];
      const int right = x + 1 < ids.cols ? row[x + 1] : 0, down = below ? below[x] : 0;
      if (id > 0 && ((right > 0 && right != id) || (down > 0 && down != id))) out[x] = 255;
    }
  }
  return borders;
}

cv::Mat renderOverlay(const places::OccupancyImage& occ, const cv::Mat& labels, const RegionMap& rm,
                      const TopologicalGraph& g, int scale, const std::vector<DoorPassage>* door_passages,
                      cv::Point frame) {
  return renderOverlay(occ, labels, regionBorders(rm.ids), g, scale, door_passages, frame);
}

cv::Mat renderOverlay(const places::OccupancyImage& occ, const cv::Mat& labels, const cv::Mat& borders,
                      const TopologicalGraph& g, int scale, const std::vector<DoorPassage>* door_passages,
                      cv::Point frame) {
  CV_Assert(borders.type() == CV_8U && borders.size() == labels.size());
  scale = overlayScaleFor(occ.cells.size(), scale);
  static const cv::Vec3b tint[] = {{235, 170, 120}, {130, 220, 130}, {90, 90, 240}};  // BGR room, corridor, door
  // The map's cells drawn straight at the overlay's scale: each output pixel takes the cell
  // cv::resize(..., INTER_NEAREST) would give it (cvFloor(pixel / scale), clamped), one row of cells at a time
  // (no full-size image of the cells).
  const int rows = occ.cells.rows, cols = occ.cells.cols;
  cv::Mat big(cvRound(rows * static_cast<double>(scale)), cvRound(cols * static_cast<double>(scale)), CV_8UC3);
  const double inv = 1.0 / scale;
  std::vector<int> col_of(static_cast<std::size_t>(big.cols));
  for (int X = 0; X < big.cols; ++X) col_of[static_cast<std::size_t>(X)] = std::min(cvFloor(X * inv), cols - 1);
  // Output rows in two halves, one per thread (each half starts with a row of its own: the same pixels).
  auto band = [&](int Y0, int Y1) {
    std::vector<cv::Vec3b> row(static_cast<std::size_t>(cols));
    int row_y = -1;
    for (int Y = Y0; Y < Y1; ++Y) {
      const int y = std::min(cvFloor(Y * inv), rows - 1);
      if (y == row_y) {  // the same cells as the output row above: a copy of it
        std::copy(big.ptr<cv::Vec3b>(Y - 1), big.ptr<cv::Vec3b>(Y - 1) + big.cols, big.ptr<cv::Vec3b>(Y));
        continue;
      }
      row_y = y;
      const unsigned char* cells = occ.cells.ptr<unsigned char>(y);
      // The labels and regions cover the map's cells from `frame` on (the whole map, or the box of the places).
      const int fy = y - frame.y, fw = labels.cols;
      const bool in_rows = fy >= 0 && fy < labels.rows;
      const unsigned char* lab = in_rows ? labels.ptr<unsigned char>(fy) : nullptr;
      const unsigned char* border = in_rows ? borders.ptr<unsigned char>(fy) : nullptr;
      const auto labelAt = [&](int x) {
        const int fx = x - frame.x;
        return lab && fx >= 0 && fx < fw ? lab[fx] : static_cast<unsigned char>(places::kNoLabel);
      };
      const auto borderAt = [&](int x) {
        const int fx = x - frame.x;
        return border && fx >= 0 && fx < fw && border[fx];
      };
      for (int x = 0; x < cols; ++x) {
        const unsigned char s = cells[x];
        // Free cells that are no place (map preparation): light grey crossed by a fine diagonal hatch.
        cv::Vec3b c = s == places::kFree       ? cv::Vec3b(255, 255, 255)
                      : s == places::kOccupied ? cv::Vec3b(0, 0, 0)
                      : s == places::kSeen     ? seenNotPlaceColour(x, y)
                                               : cv::Vec3b(180, 180, 180);
        const unsigned char l = labelAt(x);
        if (l < places::kNumLabels) c = tint[l];
        if (borderAt(x)) c = cv::Vec3b(60, 60, 60);  // region borders in dark grey
        row[static_cast<std::size_t>(x)] = c;
      }
      cv::Vec3b* out = big.ptr<cv::Vec3b>(Y);
      for (int X = 0; X < big.cols; ++X) out[X] = row[static_cast<std::size_t>(col_of[static_cast<std::size_t>(X)])];
    }
  };
  {
    std::thread second(band, big.rows / 2, big.rows);
    band(0, big.rows / 2);
    second.join();
  }
  auto px = [&](cv::Point2d p) { return cv::Point(static_cast<int>((p.x + 0.5) * scale), static_cast<int>((p.y + 0.5) * scale)); };
  auto pt = [&](const GraphNode& n) { return px(cv::Point2d(n.anchor_px)); };
  // Each edge along its routed free path. Graphs without paths (read from older files) fall back to node ->
  // contact point -> node, leaving out the half at a node whose centroid lies outside its region.
  for (const auto& e : g.edges) {
    if (e.path_px.size() >= 2) {
      std::vector<cv::Point> line;
      for (const cv::Point& q : e.path_px) line.push_back(px(cv::Point2d(q)));
      cv::polylines(big, line, false, cv::Scalar(30, 30, 30), std::max(1, scale), cv::LINE_AA);
      continue;
    }
    const GraphNode *a = g.node(e.a), *b = g.node(e.b);
    if (!a || !b) continue;
    const cv::Point c = px(e.contact_px);
    for (const GraphNode* n : {a, b})
      if (n->centroid_inside) cv::line(big, pt(*n), c, cv::Scalar(30, 30, 30), std::max(1, scale), cv::LINE_AA);
    cv::circle(big, c, scale, cv::Scalar(30, 30, 30), cv::FILLED, cv::LINE_AA);
  }
  if (door_passages)
    for (const DoorPassage& d : *door_passages)
      cv::line(big, px(d.a), px(d.b), cv::Scalar(200, 0, 200), std::max(1, scale / 2), cv::LINE_AA);
  static const cv::Scalar node_colour[] = {{160, 60, 0}, {0, 120, 0}, {0, 0, 200}};
  for (const auto& n : g.nodes) {
    const int rad = n.label == 2 ? 2 * scale : 4 * scale;
    cv::circle(big, pt(n), rad, node_colour[n.label], cv::FILLED, cv::LINE_AA);
    cv::circle(big, pt(n), rad, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    if (n.label != 2)
      cv::putText(big, std::to_string(n.id), pt(n) + cv::Point(rad + 1, -rad), cv::FONT_HERSHEY_SIMPLEX,
                  0.3 * scale, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return big;
}

void requireSixteenBitSegments(const cv::Mat& seg) {
  double mx = 0;
  cv::minMaxLoc(seg, nullptr, &mx);
  if (mx > 65535) throw std::runtime_error("segmentation has more than 65535 segments");
}

cv::Mat segmentationImage16(const cv::Mat& seg) {
  requireSixteenBitSegments(seg);
  cv::Mat out;
  seg.convertTo(out, CV_16U);
  return out;
}

cv::Vec3b segmentColour(int id) {
  if (!id) return cv::Vec3b(0, 0, 0);
  const unsigned h = static_cast<unsigned>(id) * 2654435761u;
  return cv::Vec3b(static_cast<unsigned char>(64 + (h & 0x7f)), static_cast<unsigned char>(64 + ((h >> 8) & 0xbf)),
                   static_cast<unsigned char>(64 + ((h >> 16) & 0xbf)));
}

cv::Mat colourSegmentation(const cv::Mat& seg) {
  cv::Mat out(seg.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x)
      if (const int id = seg.at<int>(y, x)) out.at<cv::Vec3b>(y, x) = segmentColour(id);
  return out;
}

}  // namespace gridtopo::topology
