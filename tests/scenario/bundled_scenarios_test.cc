// SPDX-License-Identifier: GPL-3.0-or-later
// Every bundled scenario, run through Session in this process with a controller that passes it
// and one that fails it: exactly passed (exit code 0) or failed (1), and result.json says the
// same. The command line itself is tested in tests/app.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "bundled_components.h"
#include "run_program.h"
#include "session.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Case {
  std::string scenario;
  bool passes;
  std::string controller;  // in tests/scenarios
  std::vector<std::string> sets;
  std::string robot = "unimouse";  // a bundled robot's name

  std::string Name() const {
    std::string name = scenario + "_" + (robot == "unimouse" ? "" : robot + "_") +
                       (passes ? "passes" : "fails") + "_with_" +
                       controller.substr(0, controller.find('.'));
    for (char& c : name) c = c == '-' ? '_' : c;
    return name;
  }
};

// how the test's name shows a case
void PrintTo(const Case& c, std::ostream* out) { *out << c.Name(); }

class BundledScenario : public ::testing::TestWithParam<Case> {};

TEST_P(BundledScenario, IsPassedOrFailedByItsController) {
  const Case& c = GetParam();
  PluginRegistry registry;
  AddBundledComponents(registry);
  SessionOptions options;
  options.registry = &registry;
  options.robot = UNIMOUSE_SOURCE_DIR "/robots/" + c.robot + ".yaml";
  options.scenario = UNIMOUSE_SOURCE_DIR "/scenarios/" + c.scenario + ".lua";
  options.controller = UNIMOUSE_SOURCE_DIR "/tests/scenarios/" + c.controller;
  options.sets = c.sets;
  options.out_dir = testing::FreshDirectory("scenario_" + c.Name());
  options.only_asked_pictures = true;
  options.console = false;
  std::unique_ptr<Session> session = Session::Open(options);
  while (!session->Over()) session->Step();
  const RunRecord result = session->Finish();
  ASSERT_TRUE(result.scenario.has_value());
  const ScenarioOutcome& outcome = result.scenario->outcome;
  EXPECT_EQ(result.exit_code, c.passes ? kExitPassed : kExitFailed) << result.error;
  EXPECT_EQ(outcome.status, c.passes ? "passed" : "failed") << outcome.reason;
  EXPECT_EQ(nlohmann::json::parse(ReadTextFile(options.out_dir + "/result.json")),
            RunRecordJson(result));
}

INSTANTIATE_TEST_SUITE_P(
    , BundledScenario,
    ::testing::Values(
        Case{"speed_control", true, "speed_controller.lua", {}},
        Case{"speed_control", false, "too_slow_controller.lua", {"time_limit_s=6"}},
        Case{"wall_distance", true, "wall_controller.lua", {}},
        Case{"wall_distance", false, "wrong_distance_controller.lua", {"time_limit_s=15"}},
        Case{"time_trial", true, "lap_controller.lua", {}},
        Case{"time_trial", false, "straight_controller.lua", {"time_limit_s=5"}},
        Case{"micromouse", true, "scripted_mouse.lua", {"contest_s=12"}},
        Case{"micromouse", false, "wandering_mouse.lua", {"contest_s=5"}},
        Case{"slalom", true, "slalom_controller.lua", {}},
        Case{"slalom", false, "straight_controller.lua", {}},
        // the other wheel layouts (docs/robots.md), each with its own controller
        Case{"wall_distance", true, "skid_wall_controller.lua", {}, "unimouse-skid"},
        Case{"wall_distance", true, "side_sensor_wall_controller.lua", {}, "unimouse-six"},
        // sysid passes with its firmware, which no controller stands in for
        // (SysidScenarioTest); a controller alone never logs the sequence's end
        Case{"sysid", false, "straight_controller.lua", {"time_limit_s=2"}}),
    [](const ::testing::TestParamInfo<Case>& param) { return param.param.Name(); });

}  // namespace
}  // namespace unimouse
