// gridtopo-topology-eval: per-cell label accuracy (leave-one-map-out over the labelled maps, before and after
// relaxation and after region correction) and room-segmentation precision / recall against the benchmark's
// ground truth (plain and _furnitures maps), as JSON and a Markdown table. The protocol: eval/leave_one_map_out.h.
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/eval/leave_one_map_out.h"
#include "gridtopo/eval/lomo_report.h"
#include "gridtopo/topology/topology_run_ini.h"

using namespace gridtopo;

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

    // Before any computation: the options INIs as strictly as gridtopo-topology -c reads them, and the outputs
    // writable.
    eval::LomoOptions o;
    o.topology = topology::loadTopologyOptionsIni(ini.getValue());
    for (const auto* a : {&json_arg, &md_arg})
      if (!a->getValue().empty()) checkOutputFile(a->getValue());
    if (!dump_arg.getValue().empty()) checkOutputFolder(dump_arg.getValue());
    o.training = places::loadTrainingConfig(train_ini.getValue());
    if (!order_arg.getValue().empty()) o.training.training.order = order_arg.getValue();
    if (!model_arg.getValue().empty()) o.fixed_model = places::PlacesModel::load(model_arg.getValue());
    o.fixed_model_path = model_arg.getValue();
    o.model_cache = cache_arg.getValue();
    o.prior_weight = prior_arg.getValue();
    o.segmentation = !no_seg.getValue();
    o.dump_dir = dump_arg.getValue();
    const auto maps = eval::selectMaps(places::standardLabelledMaps(dir.getValue()), maps_arg.getValue());
    const eval::LomoResult result = eval::runLeaveOneMapOut(maps, o, std::cerr);

    const std::string json = eval::lomoJson(result), md = eval::lomoMarkdown(result);
    OutputSet outs;  // the JSON and the Markdown table appear together or not at all
    if (!json_arg.getValue().empty())
      outs.write(json_arg.getValue(), [&](const std::string& p) { writeTextFileAtomically(p, json); });
    if (!md_arg.getValue().empty())
      outs.write(md_arg.getValue(), [&](const std::string& p) { writeTextFileAtomically(p, md); });
    outs.commit();
    if (json_arg.getValue().empty()) std::cout << json;
    std::cerr << md;
    return 0;
  });
}
