// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse maze ...` as users run it: the dissertation's numbers in the output, JSON, many
// mazes at once with a CSV summary, and clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "inline_assets.h"
#include "run_program.h"

namespace unimouse {
namespace {

using testing::Unimouse;
namespace fs = std::filesystem;

TEST(MazeCommandsTest, SolvePrintsBothCostsOfTable53) {
  const auto o = Unimouse("maze solve japan2018");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("modified flood fill:    cost 108"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("traditional flood fill: cost 118"), std::string::npos) << o.output;
}

TEST(MazeCommandsTest, SolveJsonCarriesPathsForTable54) {
  const auto o = Unimouse("maze solve japan2019 --json");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = nlohmann::json::parse(o.output);
  EXPECT_EQ(j[0]["modified"]["cost"], 118);
  EXPECT_EQ(j[0]["traditional"]["cost"], 120);
  EXPECT_EQ(j[0]["tie_rule"], "compass:WENS");
  EXPECT_EQ(j[0]["modified"]["cells"][0], nlohmann::json({0, 0}));
}

TEST(MazeCommandsTest, ExplorePrintsTheTripTableAndTheOptimalPath) {
  const auto o = Unimouse("maze explore japan2018");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("     1  goal     30     134"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("     3  goal    108     108"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("optimal path found: cost 108"), std::string::npos) << o.output;
}

TEST(MazeCommandsTest, ManyMazesGiveACsvSummary) {
  const fs::path dir = fs::temp_directory_path() / "unimouse_maze_cli";
  fs::remove_all(dir);
  fs::create_directories(dir / "set");
  for (int seed = 1; seed <= 3; ++seed) {
    ASSERT_EQ(Unimouse("maze generate --size 8x8 --seed " + std::to_string(seed) + " --out " +
                       (dir / "set" / ("m" + std::to_string(seed) + ".txt")).string())
                  .exit_code,
              0);
  }
  const auto o = Unimouse("maze explore " + (dir / "set").string() + " --csv " +
                          (dir / "summary.csv").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("3 mazes explored, the best path proven in 3"), std::string::npos)
      << o.output;
  std::ifstream in(dir / "summary.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "file,trips,optimal_found,best_cost,cells_visited,time_s");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 3);
  fs::remove_all(dir);
}

TEST(MazeCommandsTest, CheckFlagsAnUnreachableGoalAndStrictMakesItAnError) {
  const fs::path file = fs::temp_directory_path() / "unimouse_sealed.txt";
  std::ofstream(file) << "o---o---o---o\n| S     | G |\no---o---o---o\n";
  auto o = Unimouse("maze check " + file.string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("warning: no goal cell can be reached from the start"),
            std::string::npos);
  o = Unimouse("maze check --strict " + file.string());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  fs::remove(file);
}

TEST(MazeCommandsTest, BrokenMazeFilesAreErrorsWithTheirLocation) {
  const fs::path file = fs::temp_directory_path() / "unimouse_broken.txt";
  std::ofstream(file) << "o---o---o\n| S | X |\no---o---o\n";
  const auto o = Unimouse("maze check " + file.string());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find(file.string() + ":2:7: unexpected 'X'"), std::string::npos) << o.output;
  fs::remove(file);
}

TEST(MazeCommandsTest, GenerateWritesAMazeThatSolves) {
  const auto o = Unimouse("maze generate --size 5x7 --seed 4 --loops 0.2");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output.substr(0, 21), "o---o---o---o---o---o");
  EXPECT_EQ(Unimouse("maze generate --size 2x2").exit_code, 2);
  EXPECT_EQ(Unimouse("maze generate --size big").exit_code, 2);
}

TEST(MazeCommandsTest, BadTieRuleIsABadInput) {
  const auto o = Unimouse("maze solve japan2018 --tie compass:NNNN");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("must use each of ENWS once"), std::string::npos) << o.output;
}

TEST(MazeCommandsTest, ExploreDrawsEveryTripAndPlotDrawsAMaze) {
  const fs::path dir = fs::temp_directory_path() / "unimouse_maze_plots";
  fs::remove_all(dir);
  auto o = testing::Unimouse("maze explore japan2018 --plots " + dir.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (int trip = 1; trip <= 3; ++trip) {
    EXPECT_TRUE(fs::exists(dir / ("japan2018_trip" + std::to_string(trip) + ".png")));
    EXPECT_TRUE(fs::exists(dir / ("japan2018_trip" + std::to_string(trip) + ".svg")));
  }
  EXPECT_FALSE(fs::exists(dir / "japan2018_trip4.png"));
  o = testing::Unimouse("maze plot japan2019 --path both --costs --out " +
                        (dir / "j.svg").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream in(dir / "j.svg");
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(svg.find("class='closed-path'"), std::string::npos);
  EXPECT_NE(svg.find("class='open-path'"), std::string::npos);
  EXPECT_EQ(testing::Unimouse("maze plot japan2019 --out " + (dir / "j.gif").string()).exit_code,
            2);
  fs::remove_all(dir);
}

TEST(MazeCommandsTest, ConvertNormalisesANumFileToText) {
  const fs::path file = fs::temp_directory_path() / "unimouse_convert.num";
  std::ofstream(file) << "0 0 1 0 1 1\n1 0 1 1 1 0\n";
  const auto o = testing::Unimouse("maze convert " + file.string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output, "o---o---o\n| S   G |\no---o---o\n");
  fs::remove(file);
}

TEST(MazeCommandsTest, CheckSpeaksJsonToo) {
  const auto o = testing::Unimouse("maze check japan2018 japan2019 --json");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = nlohmann::json::parse(o.output);
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["status"], "ok");
}

}  // namespace
}  // namespace unimouse
