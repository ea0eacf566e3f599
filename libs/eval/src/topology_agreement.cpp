#include "gridtopo/eval/topology_agreement.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <iomanip>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"

namespace gridtopo::eval {

namespace {

struct Loaded {
  places::OccupancyImage occ;
  cv::Mat labels;
};

Loaded load(const TopologyOnMap& t, const topology::TopologyOptions& opt) {
  Loaded l;
  const MapImage m = io::readMap(t.map, io::MapReadOptions{});
  l.occ = places::occupancyFromMap(m, opt.freeThresholdFor(m.kind));
  const std::string path = t.topology_dir + "/labels.png";
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file not found");
  const cv::Mat codes = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (codes.empty()) throw InputError(path, "cannot read the image");
  if (codes.size() != l.occ.cells.size())
    throw InputError(path, "not the size of its map " + t.map + " (" + std::to_string(l.occ.cols()) + "x" +
                               std::to_string(l.occ.rows()) + ")");
  l.labels = places::labelsFromCodes(codes);
  return l;
}

bool isPlace(unsigned char l) { return l < places::kNumLabels; }

}  // namespace

TopologyAgreement compareTopologies(const TopologyOnMap& topology, const TopologyOnMap& reference,
                                    const topology::TopologyOptions& opt) {
  const Loaded a = load(topology, opt), b = load(reference, opt);
  TopologyAgreement r;
  r.map = topology.map;
  r.reference_map = reference.map;
  r.resolution = a.occ.resolution;
  r.reference_resolution = b.occ.resolution;
  r.labels = a.labels;
  r.alignment = alignReference(a.occ.cells == places::kFree, b.occ.cells == places::kFree, reference.map);
  // The reference's labels on our grid (no label outside its image), and ours on its grid (inverse warp).
  r.reference_labels = warpReferenceToMap(b.labels, r.alignment, a.labels.size());
  {
    cv::Mat outside = warpReferenceToMap(cv::Mat(b.labels.size(), CV_8U, cv::Scalar(1)), r.alignment, a.labels.size());
    r.reference_labels.setTo(places::kNoLabel, outside == 0);
  }
  ReferenceAlignment inverse;
  cv::invertAffineTransform(r.alignment.map_to_reference, inverse.map_to_reference);
  cv::Mat ours_there = warpReferenceToMap(a.labels, inverse, b.labels.size());
  {
    cv::Mat outside = warpReferenceToMap(cv::Mat(a.labels.size(), CV_8U, cv::Scalar(1)), inverse, b.labels.size());
    ours_there.setTo(places::kNoLabel, outside == 0);
  }
  for (int y = 0; y < a.labels.rows; ++y)
    for (int x = 0; x < a.labels.cols; ++x) {
      const unsigned char p = a.labels.at<unsigned char>(y, x), q = r.reference_labels.at<unsigned char>(y, x);
      if (isPlace(p) && isPlace(q)) {
        ++r.both;
        r.agree += p == q;
        ++r.confusion[p][q];
      } else if (isPlace(p)) {
        ++r.only_here;
      }
    }
  for (int y = 0; y < b.labels.rows; ++y)
    for (int x = 0; x < b.labels.cols; ++x)
      if (isPlace(b.labels.at<unsigned char>(y, x)) && !isPlace(ours_there.at<unsigned char>(y, x))) ++r.only_reference;
  return r;
}

std::string agreementJson(const TopologyAgreement& a) {
  std::ostringstream js;
  const auto& m = a.alignment.map_to_reference;
  js << std::setprecision(6) << "{\n  \"format\": \"gridtopo-topology-agreement\",\n  \"map\": \"" << a.map
     << "\",\n  \"reference_map\": \"" << a.reference_map << "\",\n  \"alignment\": {\"correlation\": "
     << a.alignment.correlation << ", \"map_to_reference\": [" << m(0, 0) << ", " << m(0, 1) << ", " << m(0, 2)
     << ", " << m(1, 0) << ", " << m(1, 1) << ", " << m(1, 2) << "]},\n  \"places_in_both_m2\": "
     << static_cast<double>(a.both) * a.resolution * a.resolution << ",\n  \"label_agreement\": " << a.agreement()
     << ",\n  \"places_only_in_map_m2\": " << a.onlyHereM2() << ",\n  \"places_only_in_reference_m2\": "
     << a.onlyReferenceM2() << ",\n  \"confusion_map_vs_reference\": [";
  for (int i = 0; i < 3; ++i)
    js << (i ? ", " : "") << "[" << a.confusion[i][0] << ", " << a.confusion[i][1] << ", " << a.confusion[i][2] << "]";
  js << "]\n}\n";
  return js.str();
}

std::string agreementSummary(const TopologyAgreement& a) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << "alignment correlation " << std::setprecision(3)
    << a.alignment.correlation << std::setprecision(1) << "; places in both "
    << static_cast<double>(a.both) * a.resolution * a.resolution << " m^2, labels agree on "
    << 100.0 * a.agreement() << " % of them; places only in the map " << a.onlyHereM2()
    << " m^2, only in the reference " << a.onlyReferenceM2() << " m^2";
  return o.str();
}

cv::Mat agreementOverlay(const TopologyAgreement& a) {
  cv::Mat img(a.labels.size(), CV_8UC3, cv::Scalar(90, 90, 90));
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) {
      const unsigned char p = a.labels.at<unsigned char>(y, x), q = a.reference_labels.at<unsigned char>(y, x);
      cv::Vec3b& c = img.at<cv::Vec3b>(y, x);
      if (isPlace(p) && isPlace(q)) c = p == q ? cv::Vec3b(215, 215, 215) : cv::Vec3b(40, 40, 230);
      else if (isPlace(p)) c = cv::Vec3b(220, 120, 30);
      else if (isPlace(q)) c = cv::Vec3b(0, 150, 255);
    }
  return img;
}

}  // namespace gridtopo::eval
