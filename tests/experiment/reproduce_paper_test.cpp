// scripts/reproduce_paper.sh --quick end to end: the miniature particle experiment, the Fig. 3 pipeline on the
// lab_intel plan, the 1 cm cut-out of Fig. 2 and the page with its verdicts. Asserts the figures the miniature
// gives today, so a change of the SLAM, the renderer or the report that moves them shows here.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "common/scratch.h"

namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(ReproducePaper, QuickModeWritesThePageWithItsVerdicts) {
  const auto out = gridtopo::test::scratch("paper-quick");
  const std::string cmd = "GRIDTOPO_BUILD_DIR=" + std::filesystem::path(GRIDTOPO_BIN_DIR).parent_path().string() +
                          " bash " GRIDTOPO_SOURCE_DIR "/scripts/reproduce_paper.sh --quick --out " + out.string() +
                          " > " + (out / "script.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(out / "script.log");

  // Fig. 2: the informed 15-particle run of the first 2000 Intel scans closes its first loop at scan 1839 and the
  // walls after it lie on those before.
  const auto fig2 = nlohmann::json::parse(slurp(out / "fig2.json"));
  EXPECT_EQ(fig2["loop_closure"]["later"].get<int>(), 1839);
  EXPECT_LE(fig2["walls_after_vs_before"]["median_m"].get<double>(), 0.01);
  EXPECT_GE(fig2["walls_after_vs_before"]["within_two_cells"].get<double>(), 0.85);
  // The failed Hähnel run's walls do not.
  const auto contrast = nlohmann::json::parse(slurp(out / "fig2_contrast.json"));
  EXPECT_GE(contrast["walls_after_vs_before"]["median_m"].get<double>(), 0.05);

  const std::string page = slurp(out / "paper.md");
  for (const char* row : {"| 1 | Fig. 2", "| 2 | \"Our approach", "| 3 | \"About an order", "| 4 | Fig. 3"})
    EXPECT_NE(page.find(row), std::string::npos) << row;
  EXPECT_NE(page.find("Intel: 1/1 seeds at 15, all seeds from 4 on | reproduced |"), std::string::npos) << page;
  EXPECT_NE(page.find("Intel: 60 / 4 = 15×"), std::string::npos) << page;
  EXPECT_NE(page.find("| Intel | informed (this paper) | 1/1 (0.022) | 1/1 (0.022) |  |"), std::string::npos)
      << page;
  // Fig. 3 with the Freiburg model on the plan: corridors read as rooms dominate, not missed doorways.
  EXPECT_NE(page.find("the largest error is corridor read as room"), std::string::npos) << page;
  for (const char* img : {"fig2_cutout.png", "fig2_cutout_contrast.png", "fig3_overlay.png", "success_vs_particles.png"})
    EXPECT_TRUE(std::filesystem::exists(out / "img" / img)) << img;
}
