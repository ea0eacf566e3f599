#include "gridtopo/eval/leave_one_map_out.h"

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/eval/label_views.h"
#include "gridtopo/eval/lomo_report.h"
#include "gridtopo/eval/oracle_diagnostics.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/blob_vote.h"
#include "gridtopo/topology/export.h"

namespace gridtopo::eval {

namespace fs = std::filesystem;

void MapLabelScores::add(const MapLabelScores& o) {
  before.add(o.before), after.add(o.after), corrected.add(o.corrected), segment_vote.add(o.segment_vote);
  blob_vote.add(o.blob_vote);
  oracle_region_vote.add(o.oracle_region_vote);
  oracle_region_vote_keep_doorways.add(o.oracle_region_vote_keep_doorways);
  blob_oracle.add(o.blob_oracle);
}

std::vector<places::LabelledMapFiles> selectMaps(const std::vector<places::LabelledMapFiles>& all,
                                                 const std::string& names, const std::string& option) {
  if (names.empty()) return all;
  std::vector<places::LabelledMapFiles> out;
  std::stringstream ss(names);
  for (std::string n; std::getline(ss, n, ',');) {
    bool found = false;
    for (const auto& f : all)
      if (f.name == n) out.push_back(f), found = true;
    if (!found) throw InputError(option, 0, n, "unknown map name");
  }
  return out;
}

namespace {

// The scan and feature options the samples are computed with: the fixed model's, else the training INI's; the
// scans are simulated with the topology run's threads.
std::pair<places::ScanSimulationOptions, places::FeatureOptions> sampleOptions(const LomoOptions& o) {
  places::ScanSimulationOptions scan = o.fixed_model ? o.fixed_model->scan : o.training.scan;
  scan.threads = o.topology.threads;
  return {scan, o.fixed_model ? o.fixed_model->features : o.training.features};
}

void writeImage(const std::string& dir, const std::string& name, const cv::Mat& image) {
  fs::create_directories(dir);
  cv::imwrite(dir + "/" + name, image);
}

}  // namespace

places::PlacesModel foldModel(const std::vector<places::MapSamples>& samples, std::size_t held_out,
                              const std::string& held_out_name, const LomoOptions& options,
                              const std::vector<std::optional<places::MapSamples>>& simulated) {
  if (options.fixed_model) return *options.fixed_model;
  const auto& train = options.training.training;
  std::vector<const places::MapSamples*> tr;
  for (std::size_t j = 0; j < samples.size(); ++j)
    if (j != held_out) tr.push_back(&samples[j]);
  if (tr.empty()) tr.push_back(&samples[held_out]);
  // Issue 15: the simulated SLAM-like maps of the plans ([training] simulated_maps), in every fold but the one of
  // their own building.
  for (std::size_t j = 0; j < simulated.size(); ++j)
    if (j != held_out && simulated[j]) tr.push_back(&*simulated[j]);
  const std::string cached =
      options.model_cache.empty() ? "" : options.model_cache + "/fold_" + held_out_name + ".yml";
  places::PlacesModel model;
  if (!cached.empty() && fs::exists(cached)) model = places::PlacesModel::load(cached);
  else {
    const auto [scan, feat] = sampleOptions(options);
    model = places::trainModel(tr, scan, feat, train);
    if (!cached.empty()) {
      fs::create_directories(options.model_cache);
      model.notes = "leave-one-map-out fold without " + held_out_name + ", prior_weight " +
                    std::to_string(train.prior_weight);
      model.save(cached);
    }
  }
  if (options.prior_weight >= 0) {
    if (train.prior_weight <= 0) throw InputError("--prior-weight", "needs models trained with prior_weight > 0");
    model.first.bias *= options.prior_weight / train.prior_weight;
    model.second.bias *= options.prior_weight / train.prior_weight;
  }
  return model;
}

MapLabelScores scoreLabelledMap(const places::LabelledMap& map, const places::MapSamples& samples,
                                const places::PlacesModel& model, const LomoOptions& options) {
  const topology::TopologyOptions& topo = options.topology;
  const auto lab = places::labelFromFeatures(map.occ, samples.lattice, samples.features, model, topo.relaxation,
                                             topo.threads);
  const auto res = topology::buildTopology(lab.labels, map.occ.resolution, topo, &lab);
  MapLabelScores s;
  s.map = map.name;
  s.order = places::orderName(model.order);
  s.relaxation_iterations = lab.relaxation.iterations;
  s.before.add(map.codes, lab.labels_initial);
  s.after.add(map.codes, lab.labels);
  s.corrected.add(map.codes, res.labels_corrected);
  s.segment_vote.add(map.codes, res.labels);
  if (topo.blob_vote.enabled) s.blob_vote.add(map.codes, res.labels_blob_vote);
  // The oracle diagnostics: the region vote with the ground-truth regions and the relaxed probabilities, and the
  // blob vote with the true majority of every geometric blob (the ceiling of the blob vote for these blobs).
  const cv::Mat cell_probs = topology::cellProbabilities(lab.labels, lab.lattice, lab.probs);
  s.oracle_region_vote.add(map.codes, oracleRegionVote(map.codes, lab.labels, cell_probs, false));
  s.oracle_region_vote_keep_doorways.add(map.codes,
                                         oracleRegionVote(map.codes, lab.labels, cell_probs, true));
  const cv::Mat blobs = topology::geometricBlobs(lab.labels < places::kNumLabels, map.occ.resolution, topo.blob_vote);
  s.blob_oracle.add(map.codes, blobOracleVote(map.codes, lab.labels, blobs));

  if (const std::string& dir = options.dump_dir; !dir.empty()) {
    const std::string& n = map.name;
    writeImage(dir, n + "_blobs.png",
               segmentationView(map.occ, blobs, groundTruthRegions(map.codes, lab.labels)));
    writeImage(dir, n + "_labels.png", places::labelsToCodes(res.labels));
    writeImage(dir, n + "_errors_before_relaxation.png",
               labelErrorOverlay(map.occ, map.codes, lab.labels_initial));
    writeImage(dir, n + "_errors_after_relaxation.png", labelErrorOverlay(map.occ, map.codes, lab.labels));
    writeImage(dir, n + "_errors_after_correction.png",
               labelErrorOverlay(map.occ, map.codes, res.labels_corrected));
    if (topo.seg_rules.segment_vote)
      writeImage(dir, n + "_errors_after_segment_vote.png", labelErrorOverlay(map.occ, map.codes, res.labels));
    if (topo.blob_vote.enabled)
      writeImage(dir, n + "_errors_after_blob_vote.png",
                 labelErrorOverlay(map.occ, map.codes, res.labels_blob_vote));
  }
  return s;
}

std::pair<BenchmarkRun, BenchmarkRun> scoreBenchmarkMaps(const places::LabelledMapFiles& files,
                                                         const places::PlacesModel& model, const LomoOptions& options,
                                                         std::ostream& log) {
  const topology::TopologyOptions& topo = options.topology;
  const cv::Mat gt_img = cv::imread(files.groundtruth, cv::IMREAD_UNCHANGED);
  if (gt_img.empty()) throw InputError(files.groundtruth, "cannot read ground truth");
  const cv::Mat gt = groundTruthRooms(gt_img);
  BenchmarkRun runs[2];
  for (int furn = 0; furn < 2; ++furn) {
    const std::string path = files.benchmark_map + (furn ? "_furnitures.png" : ".png");
    const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
    const auto occ = places::occupancyFromGrey(img, topo.resolution, path, topo.free_threshold);
    if (occ.cells.size() != gt.size()) throw InputError(path, "map and ground truth differ in size");
    const auto t0 = std::chrono::steady_clock::now();
    const auto l = places::labelPlaces(occ, model, topo.relaxation, topo.threads, path);
    const auto t = topology::buildTopology(l.labels, occ.resolution, topo, &l);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BenchmarkRun& run = runs[furn];
    run = {fs::path(path).stem().string(), scoreSegmentation(t.segmentation, gt), secs};
    log << "  " << run.map << ": segments " << run.score.segments << " rooms " << run.score.rooms << " precision "
        << percent(run.score.precision) << " recall " << percent(run.score.recall) << " (" << std::setprecision(3)
        << secs << " s)\n";
    if (const std::string& dir = options.dump_dir; !dir.empty()) {
      writeImage(dir, run.map + "_labels.png", places::labelsToCodes(t.labels));
      cv::Mat seg16;
      t.segmentation.convertTo(seg16, CV_16U);
      writeImage(dir, run.map + "_segmentation.png", seg16);
      writeImage(dir, run.map + "_segmentation_view.png", segmentationView(occ, t.segmentation, gt));
      writeImage(dir, run.map + "_labels_view.png", labelsView(occ, t.labels));
    }
  }
  return {runs[0], runs[1]};
}

LomoResult runLeaveOneMapOut(const std::vector<places::LabelledMapFiles>& maps, const LomoOptions& options,
                             std::ostream& log) {
  const topology::TopologyOptions& topo = options.topology;
  LomoResult result;
  result.mode = options.fixed_model ? "fixed model " + options.fixed_model_path : "leave-one-map-out";
  result.segment_vote = topo.seg_rules.segment_vote;
  result.blob_vote = topo.blob_vote.enabled;
  result.segmentation = options.segmentation;
  result.threads = topo.threads;

  // Samples (lattice, simulated scans, features, labels) of every labelled map: the fold models' training data
  // and the input of each map's own labelling.
  const auto [scan, feat] = sampleOptions(options);
  std::vector<places::LabelledMap> lmaps;
  std::vector<places::MapSamples> samples;
  {
    ProgressBar bar(maps.size(), "features (labelled maps)", "maps");
    for (const auto& f : maps) {
      lmaps.push_back(places::loadLabelledMap(f.name, f.labels, f.map, topo.resolution));
      samples.push_back(places::computeSamples(lmaps.back().occ, &lmaps.back().codes, scan, feat));
      bar.update(lmaps.size(), f.name);
    }
    bar.finish();
  }
  std::vector<std::optional<places::MapSamples>> simulated(maps.size());
  for (std::size_t i = 0; i < maps.size() && !options.fixed_model; ++i)
    if (const auto sim = places::loadSimulatedLabelledMap(maps[i], options.training.training, topo.resolution))
      simulated[i] = places::computeSamples(sim->occ, &sim->codes, scan, feat);
  ProgressBar bar(maps.size(), "leave-one-map-out", "folds");
  for (std::size_t i = 0; i < maps.size(); ++i) {
    const places::PlacesModel model = foldModel(samples, i, maps[i].name, options, simulated);
    const MapLabelScores s = scoreLabelledMap(lmaps[i], samples[i], model, options);
    result.pooled.add(s);
    result.maps.push_back(s);
    log << mapScoreLine(s, result.segment_vote, result.blob_vote) << "\n";
    if (options.segmentation) {
      auto [plain, furnished] = scoreBenchmarkMaps(maps[i], model, options, log);
      result.plain.push_back(plain);
      result.furnished.push_back(furnished);
    }
    bar.update(i + 1, maps[i].name);
  }
  bar.finish();
  return result;
}

}  // namespace gridtopo::eval
