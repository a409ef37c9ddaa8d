// SPDX-License-Identifier: GPL-3.0-or-later
// result.json as a grader reads it: what ran, each file with a SHA-256 that `sha256sum` agrees
// with, parameters and scores with their Lua types, the contest's every run; and the schema that
// every result.json the tests write is checked against (docs/result.schema.json), which refuses
// a record that is wrong.
#include "result_record.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "inline_assets.h"
#include "result_records.h"
#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

const std::string kFirmware = UNIMOUSE_FIRMWARE_DIR "/micromouse.so";
const std::string kSchema = UNIMOUSE_SOURCE_DIR "/docs/result.schema.json";

// the SHA-256 of a file as coreutils computes it
std::string Sha256sum(const std::string& file) {
  const testing::Outcome o = testing::Shell("sha256sum '" + file + "'");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  return o.output.substr(0, 64);
}

// the schema check as ResultRecordsFollowTheSchema runs it, on one record written to a file
testing::Outcome Validate(const nlohmann::json& record) {
  const std::string file = testing::FreshDirectory("schema") + "/record.json";
  WriteTextFile(file, record.dump(2));
  return testing::Shell(std::string(UNIMOUSE_PYTHON3) +
                        " " UNIMOUSE_SOURCE_DIR "/tests/support/validate_results.py " + kSchema +
                        " " + file);
}

// a short contest with the bundled firmware in the simulator's process: what ran is all there
// after half a second
nlohmann::json ShortContest(const std::string& sets) {
  const testing::RunResult run = testing::UnimouseRun(
      "--scenario micromouse --link inproc:" + kFirmware + " --duration 0.5 " + sets,
      "unimouse_short_contest");
  EXPECT_EQ(run.outcome.exit_code, 1) << run.outcome.output;  // not a single run in 0.5 s
  return run.result;
}

TEST(ResultRecordTest, TheContestRecordsEachOfItsThreeRunsWithPathCostAndWallContacts) {
  // the micromouse example's contest (docs/mazes.md): 3 runs, best 71.784 s (path cost 108), 1
  // wall contact
  const testing::RunResult run = testing::UnimouseRun(
      "--scenario micromouse --set end_on_log=done --link inproc:" + kFirmware, "unimouse_contest");
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const nlohmann::json& scenario = run.result["scenario"];
  const nlohmann::json& runs = scenario["records"]["runs"];
  ASSERT_EQ(runs.size(), 3u) << scenario.dump(2);
  EXPECT_EQ(scenario["scores"]["runs"], 3);
  int contacts_in_runs = 0;
  for (int i = 0; i < 3; ++i) {
    const nlohmann::json& r = runs[i];
    EXPECT_EQ(r["run"], i + 1);
    EXPECT_TRUE(r["path_cost"].is_number_integer()) << r;
    // japan2018's shortest path costs 108 (dissertation table 5.4, `unimouse maze solve`)
    EXPECT_GE(r["path_cost"].get<int>(), 108) << r;
    EXPECT_TRUE(r["time_s"].is_number_float()) << r;
    EXPECT_TRUE(r["wall_contacts"].is_number_integer()) << r;
    contacts_in_runs += r["wall_contacts"].get<int>();
    if (i > 0) {
      EXPECT_GT(r["start_s"].get<double>(), runs[i - 1]["start_s"].get<double>());
    }
  }
  EXPECT_EQ(runs[0]["start_s"], 0.0);
  // it never lost its position (TheMomentTheExampleMouseLosesItsPositionIsAWarning)
  EXPECT_EQ(run.result["warnings"], nlohmann::json::array());
  // the speed run is the best: the documented 71.784 s on the optimal path
  EXPECT_NEAR(runs[2]["time_s"].get<double>(), 71.784, 0.0005);
  EXPECT_EQ(runs[2]["path_cost"], 108);
  EXPECT_LT(runs[2]["time_s"].get<double>(), runs[0]["time_s"].get<double>());
  EXPECT_LT(runs[2]["time_s"].get<double>(), runs[1]["time_s"].get<double>());
  EXPECT_EQ(scenario["scores"]["best_run_s"], runs[2]["time_s"]);
  EXPECT_EQ(scenario["scores"]["best_run_path_cost"], 108);
  // contacts between the runs (on the way back to the start) count only in the total; two
  // touches less than 0.1 s apart are one contact (docs/results.md)
  EXPECT_EQ(scenario["scores"]["wall_contacts"], 1);
  EXPECT_LE(contacts_in_runs, 1);
  // the run's own list of contacts agrees
  EXPECT_EQ(run.result["contacts"].size(), 1u);
  EXPECT_EQ(run.result["robots"][0]["wall_contacts"], 1);
}

TEST(ResultRecordTest, TheMomentTheExampleMouseLosesItsPositionIsAWarning) {
  // the micromouse example loses its position in Portugal 2024's final maze: at 65.6 s it
  // believes it reached cell (11, 11), two cells north of where it is
  const std::string shared = testing::SharedMazesDir();
  if (shared.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  const testing::RunResult run =
      testing::UnimouseRun("--scenario micromouse --link inproc:" + kFirmware + " --maze " +
                               shared + "/classic/Portugal-2024-Final.txt --duration 70",
                           "unimouse_lost");
  ASSERT_EQ(run.outcome.exit_code, 1) << run.outcome.output;  // no run yet
  EXPECT_EQ(run.result["warnings"],
            nlohmann::json::array({"run: firmware reports cell (11, 11) but the robot is in cell "
                                   "(11, 9): it has lost its position"}));
  EXPECT_NE(run.outcome.output.find("[   65.600 s] run: warning: firmware reports cell (11, 11)"),
            std::string::npos)
      << run.outcome.output;
}

TEST(ResultRecordTest, ParametersKeepTheirLuaTypesFromTheFileAndFromSet) {
  const nlohmann::json r = ShortContest("--set max_runs=2 --set contest_s=12.5");
  const nlohmann::json& params = r["scenario"]["params"];
  // from the file: 60 is an integer, "" a string
  EXPECT_TRUE(params["start_within_s"].is_number_integer()) << params;
  EXPECT_EQ(params["start_within_s"], 60);
  EXPECT_EQ(params["end_on_log"], "");
  EXPECT_EQ(params["maze"], "japan2018");
  // from --set, read as Lua reads a numeral
  EXPECT_TRUE(params["max_runs"].is_number_integer()) << params;
  EXPECT_EQ(params["max_runs"], 2);
  EXPECT_TRUE(params["contest_s"].is_number_float()) << params;
  EXPECT_EQ(params["contest_s"], 12.5);
}

TEST(ResultRecordTest, TheFirmwareRobotScenarioAndMazeCarryTheirSha256) {
  const nlohmann::json r = ShortContest("");
  const nlohmann::json& link = r["driver"]["link"];
  EXPECT_EQ(link["transport"], "inproc");
  EXPECT_EQ(link["spec"], "inproc:" + kFirmware);
  EXPECT_EQ(link["profile"], "unimouse");
  EXPECT_EQ(link["firmware"]["file"], kFirmware);
  EXPECT_EQ(link["firmware"]["sha256"], Sha256sum(kFirmware));
  EXPECT_TRUE(r["driver"]["controller"].is_null());
  EXPECT_EQ(r["robot_name"], "unimouse");
  EXPECT_EQ(r["robot_sha256"], Sha256sum(r["robot"].get<std::string>()));
  EXPECT_EQ(r["scenario"]["sha256"], Sha256sum(r["scenario"]["file"].get<std::string>()));
  EXPECT_EQ(r["maze_name"], "japan2018");
  EXPECT_EQ(r["maze_sha256"], Sha256sum(r["maze"].get<std::string>()));
  EXPECT_EQ(r["maze_size"], nlohmann::json::array({16, 16}));
}

TEST(ResultRecordTest, TheRecordNamesItsSchemaAndTheProgramsVersion) {
  const nlohmann::json r = ShortContest("");
  EXPECT_EQ(r["schema"]["name"], "unimouse-result");
  EXPECT_EQ(r["schema"]["version"], kResultSchemaVersion);
  EXPECT_EQ(r["command"], "run");
  const testing::Outcome version = testing::Unimouse("--version");
  EXPECT_EQ(version.output, r["unimouse_version"].get<std::string>() + "\n");
  // the schema is the version the record names
  const nlohmann::json schema = nlohmann::json::parse(ReadTextFile(kSchema));
  EXPECT_NE(schema["title"].get<std::string>().find(std::string("version ") + kResultSchemaVersion),
            std::string::npos);
}

TEST(ResultRecordTest, AControllerIsNamedWithItsSha256) {
  const std::string controller = UNIMOUSE_SOURCE_DIR "/tests/scenarios/speed_controller.lua";
  const testing::RunResult run = testing::UnimouseRun(
      "--scenario speed_control --controller " + controller + " --duration 0.2", "unimouse_ctl");
  EXPECT_EQ(run.result["driver"]["controller"]["file"], controller);
  EXPECT_EQ(run.result["driver"]["controller"]["sha256"], Sha256sum(controller));
  EXPECT_TRUE(run.result["driver"]["link"].is_null());
  // a float in the file stays a float: 1.0, not 1 and not "1.0"
  EXPECT_TRUE(run.result["scenario"]["params"]["speed_m_per_s"].is_number_float());
}

TEST(ResultSchemaTest, ARecordAsWrittenFollowsTheSchema) {
  const testing::Outcome o = Validate(ShortContest(""));
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("1 of 1 result.json files follow"), std::string::npos) << o.output;
}

// each a record of a real run, broken in one place: the check names the place
TEST(ResultSchemaTest, AWrongRecordIsRefusedNamingWhereItIsWrong) {
  const nlohmann::json good = ShortContest("");
  struct Breakage {
    std::string what;
    nlohmann::json::json_pointer where;
    nlohmann::json value;
    std::string said;
  };
  const Breakage breakages[] = {
      {"a count as text", "/scenario/scores/runs"_json_pointer, "0", "scenario/scores/runs"},
      {"a seed as text", "/seed"_json_pointer, "1", "seed"},
      {"a hash that is not one", "/robot_sha256"_json_pointer, "abc", "robot_sha256"},
      {"a maze size of one number", "/maze_size"_json_pointer, {16}, "maze_size"},
      {"a parameter as a table",
       "/scenario/params/maze"_json_pointer,
       {{"a", 1}},
       "scenario/params/maze"},
      {"an exit code a failed run cannot have", "/exit_code"_json_pointer, 0, "exit_code"},
      {"a key the schema does not know", "/robot_file"_json_pointer, "x", "robot_file"},
  };
  for (const Breakage& b : breakages) {
    nlohmann::json bad = good;
    bad[b.where] = b.value;
    const testing::Outcome o = Validate(bad);
    EXPECT_EQ(o.exit_code, 1) << b.what << ":\n" << o.output;
    EXPECT_NE(o.output.find(b.said), std::string::npos) << b.what << ":\n" << o.output;
  }
  // and a record without its driver, or a scenario without its records
  nlohmann::json bad = good;
  bad.erase("driver");
  EXPECT_EQ(Validate(bad).exit_code, 1);
  bad = good;
  bad["scenario"].erase("records");
  EXPECT_EQ(Validate(bad).exit_code, 1);
}

TEST(ResultSchemaTest, NoRecordAtAllFailsTheCheck) {
  const testing::Outcome o =
      testing::Shell(std::string(UNIMOUSE_PYTHON3) +
                     " " UNIMOUSE_SOURCE_DIR "/tests/support/validate_results.py " + kSchema + " " +
                     testing::FreshDirectory("no_records"));
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("no result.json to validate"), std::string::npos) << o.output;
}

TEST(ResultRecordsTest, AResultATestWritesIsCopiedForTheSchemaCheck) {
  const testing::RunResult run =
      testing::UnimouseRun("--maze none --duration 0.01 --no-pictures", "unimouse_copied");
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  // the copy, made by this process, carries the test's name and the same record
  const std::string made_here = "__" + std::to_string(::getpid()) + "_";
  int copies = 0;
  for (const auto& entry : fs::directory_iterator(UNIMOUSE_RESULT_RECORDS_DIR)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("ResultRecordsTest.AResultATestWritesIsCopiedForTheSchemaCheck__") &&
        name.find("unimouse_copied_result.json" + made_here) != std::string::npos) {
      EXPECT_EQ(nlohmann::json::parse(ReadTextFile(entry.path().string())), run.result);
      ++copies;
    }
  }
  EXPECT_EQ(copies, 1);
}

}  // namespace
}  // namespace unimouse
