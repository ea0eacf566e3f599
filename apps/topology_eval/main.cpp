// gridtopo-topology-eval: per-cell label accuracy (leave-one-map-out over the labelled maps, before and after
// relaxation and after region correction) and room-segmentation precision / recall against the benchmark's
// ground truth (plain and _furnitures maps), as JSON and a Markdown table.
#include <mrpt/config/CConfigFile.h>
#include <tclap/CmdLine.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/training.h"
#include "gridtopo/topology/blob_vote.h"
#include "gridtopo/topology/evaluation.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {

struct MeanStd {
  std::vector<double> v;
  double mean() const {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / static_cast<double>(v.size());
  }
  double std() const {
    if (v.size() < 2) return 0;
    const double m = mean();
    double s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  }
};

std::string pct(double v) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << 100.0 * v;
  return o.str();
}

// Error overlay of one labelled map: the map in grey, correctly labelled cells in a pale colour of their label,
// wrongly labelled cells in the saturated colour of the predicted label (room blue, corridor green, doorway red),
// labelled cells without a prediction in black.

// Segmentation of a benchmark map for viewing: segments in colours, segment borders black, non-free cells grey,
// and the ground-truth room borders (free cells next to a ground-truth door line) red.
cv::Mat segmentationView(const places::OccupancyImage& occ, const cv::Mat& seg, const cv::Mat& gt) {
  cv::Mat out = topology::colourSegmentation(seg);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      cv::Vec3b& o = out.at<cv::Vec3b>(r, c);
      if (!occ.isFree(r, c)) {
        o = cv::Vec3b(110, 110, 110);
        continue;
      }
      const int s = seg.at<int>(r, c), g = gt.at<int>(r, c);
      bool seg_border = false, gt_border = g <= 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int rr = r + dy, cc = c + dx;
          if (rr < 0 || cc < 0 || rr >= out.rows || cc >= out.cols || !occ.isFree(rr, cc)) continue;
          if (seg.at<int>(rr, cc) != s) seg_border = true;
          if (g > 0 && gt.at<int>(rr, cc) != g) gt_border = true;
        }
      if (gt_border) o = cv::Vec3b(0, 0, 255);
      else if (seg_border) o = cv::Vec3b(0, 0, 0);
    }
  return out;
}

// Labels of a map for viewing: room blue, corridor green, doorway red, non-free grey, free unlabelled white.
cv::Mat labelsView(const places::OccupancyImage& occ, const cv::Mat& labels) {
  cv::Mat out(labels.size(), CV_8UC3);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const int l = labels.at<unsigned char>(r, c);
      out.at<cv::Vec3b>(r, c) = !occ.isFree(r, c) ? cv::Vec3b(110, 110, 110)
                                : l < places::kNumLabels ? topology::kLabelColoursBgr[l] : cv::Vec3b(255, 255, 255);
    }
  return out;
}

struct SegRun {
  std::string map;
  topology::SegmentationScore score;
  double seconds = 0;
};

}  // namespace

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-topology-eval", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Evaluate place labelling and room segmentation on the labelled maps of datasets/places: leave-one-map-out "
        "cell accuracy (before/after relaxation, after region correction) and segmentation precision/recall on the "
        "benchmark maps (plain and _furnitures) with the model that did not see that building.",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> dir("d", "places-dir", "datasets/places directory", false, "datasets/places", "dir", cmd);
    TCLAP::ValueArg<std::string> ini("c", "ini", "topology INI (config-ini/topology.ini)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> train_ini("t", "train-ini", "training INI (config-ini/topology_train.ini)", false, "",
                                           "file", cmd);
    TCLAP::ValueArg<std::string> model_arg("m", "model",
                                           "use this model for every map instead of leave-one-map-out training "
                                           "(optimistic when the model saw the map)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> maps_arg("", "maps", "comma-separated subset of map names (default: all 9)", false, "",
                                          "names", cmd);
    TCLAP::ValueArg<std::string> json_arg("j", "json", "write the results as JSON here", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> md_arg("", "markdown", "write a Markdown table here", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> dump_arg("", "dump-dir", "write label/segmentation images and error overlays (pale = right, saturated = wrong, in the colour of the predicted label) per map here, and for every benchmark map MAP_segmentation_view.png (segments in colours, ground-truth room borders red) and MAP_labels_view.png", false, "",
                                          "dir", cmd);
    TCLAP::ValueArg<std::string> order_arg("", "fold-order",
                                           "decision-list order for the leave-one-map-out folds: auto (validation "
                                           "inside each fold, slow) or e.g. doorway,room,corridor; default: the "
                                           "training INI's order", false, "", "order", cmd);
    TCLAP::ValueArg<std::string> cache_arg("", "model-cache",
                                           "directory for the fold models: loaded if present, else trained and saved "
                                           "(lets option studies skip retraining)", false, "", "dir", cmd);
    TCLAP::ValueArg<double> prior_arg("", "prior-weight",
                                      "rescale the fold models' prior correction to this weight (trained with the "
                                      "training INI's prior_weight)", false, -1, "w", cmd);
    TCLAP::SwitchArg no_seg("", "no-segmentation", "skip the room-segmentation benchmark", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const topology::TopologyOptions topo = topology::loadTopologyOptions(ini.getValue());
    auto [train, scan, feat] = places::loadTrainingConfig(train_ini.getValue());
    if (!order_arg.getValue().empty()) train.order = order_arg.getValue();
    scan.threads = topo.threads;
    std::optional<places::PlacesModel> fixed_model;
    if (!model_arg.getValue().empty()) {
      fixed_model = places::PlacesModel::load(model_arg.getValue());
      scan = fixed_model->scan;
      scan.threads = topo.threads;
      feat = fixed_model->features;
    }

    auto all = places::standardLabelledMaps(dir.getValue());
    std::vector<places::LabelledMapFiles> files;
    if (maps_arg.getValue().empty()) files = all;
    else {
      std::stringstream ss(maps_arg.getValue());
      for (std::string n; std::getline(ss, n, ',');) {
        bool found = false;
        for (const auto& f : all)
          if (f.name == n) files.push_back(f), found = true;
        if (!found) throw InputError("--maps", 0, n, "unknown map name");
      }
    }
    // Features of all labelled maps (for training and label accuracy).
    std::vector<places::LabelledMap> lmaps;
    std::vector<places::MapSamples> samples;
    {
      ProgressBar bar(files.size(), "features (labelled maps)", "maps");
      for (const auto& f : files) {
        lmaps.push_back(places::loadLabelledMap(f.name, f.labels, f.map, topo.resolution));
        samples.push_back(places::computeSamples(lmaps.back().occ, &lmaps.back().codes, scan, feat));
        bar.update(lmaps.size(), f.name);
      }
      bar.finish();
    }
    // Issue 15: the simulated SLAM-like maps of the plans ([training] simulated_maps), trained on in every fold but
    // the one of their own building.
    std::vector<std::optional<places::MapSamples>> sim_samples(files.size());
    for (std::size_t i = 0; i < files.size() && !fixed_model; ++i)
      if (const auto sim = places::loadSimulatedLabelledMap(files[i], train, topo.resolution))
        sim_samples[i] = places::computeSamples(sim->occ, &sim->codes, scan, feat);
    topology::ConfusionMatrix total_before, total_after, total_corrected, total_voted, total_blob, total_oracle,
        total_oracle_keep, total_blob_oracle;
    const bool vote = topo.seg_rules.segment_vote, blob = topo.blob_vote.enabled;
    std::ostringstream per_map;
    std::vector<SegRun> seg_plain, seg_furn;
    MeanStd loo_after;
    ProgressBar bar(files.size(), "leave-one-map-out", "folds");
    for (std::size_t i = 0; i < files.size(); ++i) {
      places::PlacesModel model;
      std::vector<places::OrderScore> val;
      if (fixed_model) model = *fixed_model;
      else {
        std::vector<const places::MapSamples*> tr;
        for (std::size_t j = 0; j < files.size(); ++j)
          if (j != i) tr.push_back(&samples[j]);
        if (tr.empty()) tr.push_back(&samples[i]);
        for (std::size_t j = 0; j < files.size(); ++j)
          if (j != i && sim_samples[j]) tr.push_back(&*sim_samples[j]);
        const std::string cached = cache_arg.getValue().empty() ? ""
                                   : cache_arg.getValue() + "/fold_" + files[i].name + ".yml";
        if (!cached.empty() && fs::exists(cached)) model = places::PlacesModel::load(cached);
        else {
          model = places::trainModel(tr, scan, feat, train, &val);
          if (!cached.empty()) {
            fs::create_directories(cache_arg.getValue());
            model.notes = "leave-one-map-out fold without " + files[i].name + ", prior_weight " +
                          std::to_string(train.prior_weight);
            model.save(cached);
          }
        }
        if (prior_arg.getValue() >= 0) {
          if (train.prior_weight <= 0) throw InputError("--prior-weight", "needs models trained with prior_weight > 0");
          model.first.bias *= prior_arg.getValue() / train.prior_weight;
          model.second.bias *= prior_arg.getValue() / train.prior_weight;
        }
      }
      const auto lab = places::labelFromFeatures(lmaps[i].occ, samples[i].lattice, samples[i].features, model,
                                                 topo.relaxation, topo.threads);
      const auto topo_res = topology::buildTopology(lab.labels, lmaps[i].occ.resolution, topo, &lab);
      topology::ConfusionMatrix before, after, corrected, voted, blob_voted, oracle, oracle_keep, blob_oracle;
      before.add(lmaps[i].codes, lab.labels_initial);
      after.add(lmaps[i].codes, lab.labels);
      corrected.add(lmaps[i].codes, topo_res.labels_corrected);
      voted.add(lmaps[i].codes, topo_res.labels);
      if (blob) blob_voted.add(lmaps[i].codes, topo_res.labels_blob_vote);
      total_before.add(before), total_after.add(after), total_corrected.add(corrected), total_voted.add(voted);
      total_blob.add(blob_voted);
      // Diagnostics (round 5): the oracle region vote (ground-truth regions, relaxed probabilities) and the blob
      // vote with the true majority of every geometric blob (the ceiling of the blob vote for these blobs).
      const cv::Mat cell_probs = topology::cellProbabilities(lab.labels, lab.lattice, lab.probs);
      oracle.add(lmaps[i].codes, topology::oracleRegionVote(lmaps[i].codes, lab.labels, cell_probs, false));
      oracle_keep.add(lmaps[i].codes, topology::oracleRegionVote(lmaps[i].codes, lab.labels, cell_probs, true));
      {
        cv::Mat truth_onehot(lab.labels.size(), CV_32FC3, cv::Scalar::all(0));
        for (int r = 0; r < truth_onehot.rows; ++r)
          for (int c = 0; c < truth_onehot.cols; ++c) {
            const int t = places::labelFromCode(lmaps[i].codes.at<unsigned char>(r, c));
            if (t >= 0) truth_onehot.at<cv::Vec3f>(r, c)[t] = 1.0f;
          }
        const cv::Mat blobs =
            topology::geometricBlobs(lab.labels < places::kNumLabels, lmaps[i].occ.resolution, topo.blob_vote);
        blob_oracle.add(lmaps[i].codes, topology::voteLabelsInAreas(lab.labels, blobs, truth_onehot));
        if (!dump_arg.getValue().empty()) {
          fs::create_directories(dump_arg.getValue());
          cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_blobs.png",
                      segmentationView(lmaps[i].occ, blobs, topology::groundTruthRegions(lmaps[i].codes, lab.labels)));
        }
      }
      total_oracle.add(oracle), total_oracle_keep.add(oracle_keep), total_blob_oracle.add(blob_oracle);
      loo_after.v.push_back(after.accuracy());
      per_map << (i ? ",\n" : "") << "    {\"map\": \"" << files[i].name << "\", \"order\": \""
              << places::orderName(model.order) << "\", \"relaxation_iterations\": " << lab.relaxation.iterations
              << ", \"accuracy_before\": " << before.accuracy() << ", \"accuracy_after\": " << after.accuracy()
              << ", \"accuracy_corrected\": " << corrected.accuracy()
              << (vote ? ", \"accuracy_segment_vote\": " + std::to_string(voted.accuracy()) : std::string())
              << (blob ? ", \"accuracy_blob_vote\": " + std::to_string(blob_voted.accuracy()) : std::string())
              << ", \"oracle_region_vote_accuracy\": " << oracle.accuracy()
              << ", \"oracle_region_vote_keep_doorways_accuracy\": " << oracle_keep.accuracy()
              << ", \"blob_oracle_accuracy\": " << blob_oracle.accuracy()
              << ", \"doorway_recall_before\": "
              << before.recall(2) << ", \"doorway_recall_after\": " << after.recall(2)
              << ", \"after_relaxation\": " << after.toJson(6) << "}";
      std::cerr << files[i].name << ": order " << places::orderName(model.order) << " acc before "
                << pct(before.accuracy()) << " after " << pct(after.accuracy()) << " corrected "
                << pct(corrected.accuracy()) << (vote ? " vote " + pct(voted.accuracy()) : std::string())
                << (blob ? " blob vote " + pct(blob_voted.accuracy()) : std::string()) << " oracle region vote "
                << pct(oracle.accuracy()) << " (keeping doorways " << pct(oracle_keep.accuracy()) << ") blob oracle "
                << pct(blob_oracle.accuracy()) << " door recall " << pct(before.recall(2)) << "/"
                << pct(after.recall(2)) << "\n";
      if (!dump_arg.getValue().empty()) {
        fs::create_directories(dump_arg.getValue());
        cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_labels.png", places::labelsToCodes(topo_res.labels));
        cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_errors_before_relaxation.png",
                    topology::labelErrorOverlay(lmaps[i].occ, lmaps[i].codes, lab.labels_initial));
        cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_errors_after_relaxation.png",
                    topology::labelErrorOverlay(lmaps[i].occ, lmaps[i].codes, lab.labels));
        cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_errors_after_correction.png",
                    topology::labelErrorOverlay(lmaps[i].occ, lmaps[i].codes, topo_res.labels_corrected));
        if (vote)
          cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_errors_after_segment_vote.png",
                      topology::labelErrorOverlay(lmaps[i].occ, lmaps[i].codes, topo_res.labels));
        if (blob)
          cv::imwrite(dump_arg.getValue() + "/" + files[i].name + "_errors_after_blob_vote.png",
                      topology::labelErrorOverlay(lmaps[i].occ, lmaps[i].codes, topo_res.labels_blob_vote));
      }
      if (!no_seg.getValue()) {
        const cv::Mat gt_img = cv::imread(files[i].groundtruth, cv::IMREAD_UNCHANGED);
        if (gt_img.empty()) throw InputError(files[i].groundtruth, "cannot read ground truth");
        const cv::Mat gt = topology::groundTruthRooms(gt_img);
        for (int furn = 0; furn < 2; ++furn) {
          const std::string path = files[i].benchmark_map + (furn ? "_furnitures.png" : ".png");
          const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
          const auto occ = places::occupancyFromGrey(img, topo.resolution, path, topo.free_threshold);
          if (occ.cells.size() != gt.size()) throw InputError(path, "map and ground truth differ in size");
          const auto t0 = std::chrono::steady_clock::now();
          const auto l = places::labelPlaces(occ, model, topo.relaxation, topo.threads, path);
          const auto t = topology::buildTopology(l.labels, occ.resolution, topo, &l);
          const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          SegRun run{fs::path(path).stem().string(), topology::scoreSegmentation(t.segmentation, gt), secs};
          std::cerr << "  " << run.map << ": segments " << run.score.segments << " rooms " << run.score.rooms
                    << " precision " << pct(run.score.precision) << " recall " << pct(run.score.recall) << " ("
                    << std::setprecision(3) << secs << " s)\n";
          (furn ? seg_furn : seg_plain).push_back(run);
          if (!dump_arg.getValue().empty()) {
            cv::imwrite(dump_arg.getValue() + "/" + run.map + "_labels.png", places::labelsToCodes(t.labels));
            cv::Mat seg16;
            t.segmentation.convertTo(seg16, CV_16U);
            cv::imwrite(dump_arg.getValue() + "/" + run.map + "_segmentation.png", seg16);
            cv::imwrite(dump_arg.getValue() + "/" + run.map + "_segmentation_view.png",
                        segmentationView(occ, t.segmentation, gt));
            cv::imwrite(dump_arg.getValue() + "/" + run.map + "_labels_view.png", labelsView(occ, t.labels));
          }
        }
      }
      bar.update(i + 1, files[i].name);
    }
    bar.finish();

    auto segSummary = [](const std::vector<SegRun>& runs, MeanStd& p, MeanStd& r, MeanStd& t, MeanStd& pw,
                         MeanStd& rw) {
      for (const auto& x : runs) {
        p.v.push_back(x.score.precision), r.v.push_back(x.score.recall), t.v.push_back(x.seconds);
        pw.v.push_back(x.score.precision_weighted), rw.v.push_back(x.score.recall_weighted);
      }
    };
    MeanStd pp, pr, pt, fp, fr, ft, ppw, prw, fpw, frw;
    segSummary(seg_plain, pp, pr, pt, ppw, prw);
    segSummary(seg_furn, fp, fr, ft, fpw, frw);

    std::ostringstream js;
    js << "{\n  \"mode\": \"" << (fixed_model ? "fixed model " + model_arg.getValue() : "leave-one-map-out") << "\",\n"
       << "  \"labels\": {\n    \"before_relaxation\": " << total_before.toJson(4)
       << ",\n    \"after_relaxation\": " << total_after.toJson(4) << ",\n    \"after_correction\": "
       << total_corrected.toJson(4)
       << (vote ? ",\n    \"after_segment_vote\": " + total_voted.toJson(4) : std::string())
       << (blob ? ",\n    \"after_blob_vote\": " + total_blob.toJson(4) : std::string())
       << ",\n    \"oracle_region_vote_accuracy\": " << total_oracle.accuracy()
       << ",\n    \"oracle_region_vote\": " << total_oracle.toJson(4)
       << ",\n    \"oracle_region_vote_keep_doorways_accuracy\": " << total_oracle_keep.accuracy()
       << ",\n    \"blob_oracle_accuracy\": " << total_blob_oracle.accuracy() << ",\n    \"per_map\": [\n" << per_map.str() << "\n    ]\n  }";
    auto segJson = [&](const char* name, const std::vector<SegRun>& runs, const MeanStd& p, const MeanStd& r,
                       const MeanStd& t) {
      js << ",\n  \"" << name << "\": {\"precision_mean\": " << p.mean() << ", \"precision_std\": " << p.std()
         << ", \"recall_mean\": " << r.mean() << ", \"recall_std\": " << r.std() << ", \"seconds_mean\": " << t.mean()
         << ", \"maps\": [";
      for (std::size_t k = 0; k < runs.size(); ++k)
        js << (k ? ", " : "") << "\n      {\"map\": \"" << runs[k].map << "\", \"score\": " << runs[k].score.toJson()
           << ", \"seconds\": " << runs[k].seconds << "}";
      js << "]}";
    };
    if (!no_seg.getValue()) {
      segJson("segmentation_plain", seg_plain, pp, pr, pt);
      segJson("segmentation_furnitures", seg_furn, fp, fr, ft);
    }
    js << "\n}\n";
    if (!json_arg.getValue().empty()) writeTextFileAtomically(json_arg.getValue(), js.str());
    else std::cout << js.str();

    std::ostringstream md;
    md << "| measure | value |\n|---|---|\n"
       << "| cell accuracy before relaxation (pooled over maps) | " << pct(total_before.accuracy()) << " % |\n"
       << "| cell accuracy after relaxation (pooled) | " << pct(total_after.accuracy()) << " % |\n"
       << (blob ? "| cell accuracy after blob vote, before correction (pooled) | " + pct(total_blob.accuracy()) + " % |\n"
                : std::string())
       << "| cell accuracy after region correction (pooled) | " << pct(total_corrected.accuracy()) << " % |\n"
       << (vote ? "| cell accuracy after region correction and segment vote (pooled) | " + pct(total_voted.accuracy()) +
                      " % |\n"
                : std::string())
       << "| diagnostic: oracle region vote (ground-truth regions, relaxed probabilities; pooled) | "
       << pct(total_oracle.accuracy()) << " % (predicted doorways kept: " << pct(total_oracle_keep.accuracy())
       << " %) |\n"
       << "| diagnostic: blob oracle (geometric blobs voted with their true majority; pooled) | "
       << pct(total_blob_oracle.accuracy()) << " % |\n"
       << "| cell accuracy after relaxation, mean ± std over maps | " << pct(loo_after.mean()) << " ± "
       << pct(loo_after.std()) << " % |\n"
       << "| recall room / corridor / doorway (after relaxation) | " << pct(total_after.recall(0)) << " / "
       << pct(total_after.recall(1)) << " / " << pct(total_after.recall(2)) << " % |\n"
       << "| precision room / corridor / doorway (after relaxation) | " << pct(total_after.precision(0)) << " / "
       << pct(total_after.precision(1)) << " / " << pct(total_after.precision(2)) << " % |\n"
       << "| doorway recall before → after relaxation | " << pct(total_before.recall(2)) << " → "
       << pct(total_after.recall(2)) << " % |\n";
    if (!no_seg.getValue())
      md << "| segmentation unfurnished: recall / precision (mean ± std over maps) | " << pct(pr.mean()) << " ± "
         << pct(pr.std()) << " / " << pct(pp.mean()) << " ± " << pct(pp.std()) << " % |\n"
         << "| segmentation furnished: recall / precision | " << pct(fr.mean()) << " ± " << pct(fr.std()) << " / "
         << pct(fp.mean()) << " ± " << pct(fp.std()) << " % |\n"
         << "| segmentation unfurnished, pixel-weighted: recall / precision | " << pct(prw.mean()) << " ± "
         << pct(prw.std()) << " / " << pct(ppw.mean()) << " ± " << pct(ppw.std()) << " % |\n"
         << "| segmentation furnished, pixel-weighted: recall / precision | " << pct(frw.mean()) << " ± "
         << pct(frw.std()) << " / " << pct(fpw.mean()) << " ± " << pct(fpw.std()) << " % |\n"
         << "| segments / ground-truth rooms (sum over maps), unfurnished; furnished | " << [&] {
              int s = 0, r = 0, s2 = 0;
              for (const auto& x : seg_plain) s += x.score.segments, r += x.score.rooms;
              for (const auto& x : seg_furn) s2 += x.score.segments;
              return std::to_string(s) + " / " + std::to_string(r) + "; " + std::to_string(s2) + " / " + std::to_string(r);
            }() << " |\n"
         << "| seconds per benchmark map (labelling + topology, " << topo.threads << " threads) | "
         << std::setprecision(3) << pt.mean() << " (plain), " << ft.mean() << " (furnished) |\n";
    if (!md_arg.getValue().empty()) writeTextFileAtomically(md_arg.getValue(), md.str());
    std::cerr << md.str();
    return 0;
  });
}
