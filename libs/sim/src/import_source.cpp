#include "gridtopo/sim/import_source.h"

#include <stdexcept>
#include <utility>

#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/simulator.h"

namespace gridtopo::sim {

ImportSource readImportSource(const std::optional<std::string>& input, const std::optional<std::size_t>& simulate,
                              unsigned seed, const std::optional<std::string>& ground_truth,
                              const io::LogReadOptions& read, OutputSet& outputs) {
  if (simulate.has_value() == input.has_value()) throw std::invalid_argument("give either --input or --simulate");
  if (ground_truth && !simulate) throw std::invalid_argument("--ground-truth needs --simulate");
  ImportSource source;
  if (input) {
    source.name = *input;
    source.scans = io::readScanLog(*input, read, source.info);
    return source;
  }
  SimOptions options = pillarRoomOptions();
  options.seed = seed;
  SimLog log = simulatePillarRoom(*simulate, options);
  const std::vector<TimedPose> truth = log.timedTruth();
  source.scans = std::move(log.records);
  source.info.format = io::LogFormat::Simulated;
  source.name = "simulated (" + std::to_string(*simulate) + " scans, seed " + std::to_string(options.seed) + ")";
  if (ground_truth) {
    const std::string header = "ground truth of gridtopo-import --simulate " + std::to_string(*simulate) + " --seed " +
                               std::to_string(options.seed);
    outputs.write(*ground_truth, [truth, header](const std::string& tmp) { io::writeTrajectory(tmp, truth, {header}); });
  }
  return source;
}

}  // namespace gridtopo::sim
