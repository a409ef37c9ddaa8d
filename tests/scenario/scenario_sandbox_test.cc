// SPDX-License-Identifier: GPL-3.0-or-later
// Scenarios in this process, without a run: loading turns whatever a file returns into a clean
// one-line error, never a crash; each scenario has its own instruction budget, which no pcall
// can swallow; errors in the prelude's helpers name the scenario's line.
#include <gtest/gtest.h>
#include <lua5.4/lua.h>

#include <filesystem>
#include <string>
#include <vector>

#include "scenario.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

// writes a scenario file of the test's own in the build tree and returns its path
std::string WriteScenario(const std::string& text, const std::string& suffix = "") {
  const fs::path dir = fs::path(UNIMOUSE_BINARY_DIR) / "tests" / "scenario_files";
  fs::create_directories(dir);
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path file =
      dir / (std::string(test->test_suite_name()) + "." + test->name() + suffix + ".lua");
  WriteTextFile(file.string(), text);
  return file.string();
}

// a file's name as Lua shows it in a message: a long path keeps only its last characters
std::string Shown(const std::string& path) {
  constexpr size_t kKept = LUA_IDSIZE - 4;  // after "...", before the terminating zero
  return path.size() + 1 <= LUA_IDSIZE ? path : "..." + path.substr(path.size() - kKept);
}

// the script error loading the file gives; "" when it loads
std::string LoadError(const std::string& path) {
  try {
    Scenario::Load(path, {}, 1);
  } catch (const RuntimeFault& e) {
    return e.what();
  }
  return "";
}

// the script error building the world gives; "" when there is none
std::string WorldError(const std::string& path) {
  try {
    Scenario::Load(path, {}, 1)->BuildWorld();
  } catch (const RuntimeFault& e) {
    return e.what();
  }
  return "";
}

constexpr const char* kBudgetSpent =
    "instruction budget exhausted: a loop that never waits (use sim.wait)?";

TEST(ScenarioLoadTest, ATableWithoutANameIsAScriptErrorNamingTheFile) {
  const std::string path = WriteScenario("return { run = function() end }\n");
  EXPECT_EQ(LoadError(path), path + ": the scenario's name is missing or not a string");
}

TEST(ScenarioLoadTest, AFileThatReturnsNoTableIsAScriptError) {
  const std::string path = WriteScenario("return 42\n");
  EXPECT_EQ(LoadError(path),
            path + ": a scenario file returns sim.scenario { name = ..., run = ... }");
}

TEST(ScenarioLoadTest, AnIndexMetamethodThatFailsGivesItsFileAndLine) {
  const std::string path = WriteScenario(
      "return setmetatable({}, { __index = function(_, key)\n"
      "  error('no ' .. key .. ' here')\n"
      "end })\n");
  EXPECT_EQ(LoadError(path), Shown(path) + ":2: no name here");
}

TEST(ScenarioLoadTest, AParameterNameThatIsNotAStringIsAScriptError) {
  const std::string path = WriteScenario(
      "return sim.scenario { name = 'keys', params = { 0.5, speed = 1 },\n"
      "                      run = function() end }\n");
  EXPECT_EQ(LoadError(path), path + ": params has a number key; parameter names are strings");
}

TEST(ScenarioLoadTest, AParameterWhoseTostringFailsIsAScriptErrorWithItsLine) {
  const std::string path = WriteScenario(
      "local odd = setmetatable({}, { __tostring = function()\n"
      "  error('cannot be said')\n"
      "end })\n"
      "return sim.scenario { name = 'odd', params = { odd = odd }, run = function() end }\n");
  EXPECT_EQ(LoadError(path), path + ": parameter 'odd' cannot be shown as text: " + Shown(path) +
                                 ":2: cannot be said");
}

TEST(ScenarioLoadTest, AParameterWhoseTostringGivesNoTextIsAScriptError) {
  const std::string path = WriteScenario(
      "local odd = setmetatable({}, { __tostring = function() return {} end })\n"
      "return sim.scenario { name = 'odd', params = { odd = odd }, run = function() end }\n");
  EXPECT_EQ(LoadError(path), path +
                                 ": parameter 'odd' cannot be shown as text: '__tostring' must "
                                 "return a string");
}

TEST(ScenarioLoadTest, AnErrorValueThatIsNotTextIsNamedByItsType) {
  const std::string path = WriteScenario("error({})\n");
  EXPECT_EQ(LoadError(path), "(error object is a table value)");
}

TEST(ScenarioLoadTest, OverridesTakeTheTypeOfTheirParameterAndSetTheTimeLimit) {
  const std::string path = WriteScenario(
      "return sim.scenario { name = 'limits', params = { time_limit_s = 60, label = 'a' },\n"
      "                      run = function() end }\n");
  const auto s = Scenario::Load(path, {{"time_limit_s", "7.5"}, {"label", "b"}}, 1);
  EXPECT_EQ(s->name(), "limits");
  EXPECT_DOUBLE_EQ(s->time_limit_s(), 7.5);
  EXPECT_EQ(s->params().at("label"), "b");
  EXPECT_THROW(Scenario::Load(path, {{"time_limit_s", "soon"}}, 1), InputError);
  EXPECT_THROW(Scenario::Load(path, {{"speed", "1"}}, 1), InputError);
}

TEST(ScenarioBudgetTest, APcallCannotSwallowTheSpentBudget) {
  const std::string path = WriteScenario(
      "return sim.scenario { name = 'swallow', run = function() end, world = function()\n"
      "  while true do\n"
      "    pcall(function() while true do end end)\n"
      "  end\n"
      "end }\n");
  EXPECT_EQ(WorldError(path), path + ":3: " + kBudgetSpent + " (in world)");
}

TEST(ScenarioBudgetTest, NeitherCanXpcallNorACoroutine) {
  const std::vector<std::string> catchers = {
      "xpcall(function() while true do end end, function(e) return e end)",
      "coroutine.resume(coroutine.create(function() while true do end end))",
      "coroutine.wrap(function() pcall(function() while true do end end) end)()",
  };
  for (size_t i = 0; i < catchers.size(); ++i) {
    const std::string path = WriteScenario(
        "return sim.scenario { name = 'swallow', run = function() end, world = function()\n"
        "  while true do pcall(function()\n"
        "    " +
            catchers[i] +
            "\n"
            "  end) end\n"
            "end }\n",
        std::to_string(i));
    EXPECT_NE(WorldError(path).find(path + ":3: " + kBudgetSpent), std::string::npos)
        << catchers[i] << ": " << WorldError(path);
  }
}

TEST(ScenarioBudgetTest, TwoScenariosInOneProcessKeepSeparateBudgets) {
  // while the first scenario's world runs, it asks for a picture, and the picture taker builds
  // a second scenario's world: 5 + 18 + 5 million instructions in all, each scenario under 20
  const std::string first = WriteScenario(
      "return sim.scenario { name = 'first', run = function() end, world = function()\n"
      "  for i = 1, 5e6 do end\n"
      "  sim.snapshot_save('x.png')\n"
      "  for i = 1, 5e6 do end\n"
      "end }\n",
      "_first");
  const std::string second = WriteScenario(
      "return sim.scenario { name = 'second', run = function() end, world = function()\n"
      "  for i = 1, 18e6 do end\n"
      "end }\n",
      "_second");
  std::string second_error = "not built";
  const auto a = Scenario::Load(first, {}, 1);
  a->SetPictureTaker([&](const std::string&, const std::string&, int, int) {
    second_error = WorldError(second);
    return std::string();
  });
  EXPECT_NO_THROW(a->BuildWorld());
  EXPECT_EQ(second_error, "");
}

TEST(ScenarioBudgetTest, EachCallIntoLuaHasAFreshBudget) {
  const std::string path = WriteScenario(
      "for i = 1, 15e6 do end\n"
      "return sim.scenario { name = 'fresh', run = function() end, world = function()\n"
      "  for i = 1, 15e6 do end\n"
      "end }\n");
  EXPECT_EQ(WorldError(path), "");
}

TEST(ScenarioPreludeTest, HelperErrorsNameTheScenariosLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sim.wall_polyline { points = { { 0, 0 } } }",
       "sim.wall_polyline{points = {{x_m, y_m}, ...}}: at least two points"},
      {"sim.wall_polyline { points = { { 0, 0 }, 'north' } }",
       "sim.wall_polyline: point 2 is not {x_m, y_m}"},
      {"sim.wall_polyline { points = { { 0, 0 }, { 0, 0 } } }",
       "a wall needs a length, thickness and height"},
      {"sim.wall_arc { cx_m = 0, cy_m = 0, radius_m = 1, from_deg = 0 }",
       "sim.wall_arc: field 'to_deg' is a number"},
      {"sim.gate_add { name = 'finish', x1_m = 0, y1_m = 0, x2_m = 1 }",
       "sim.gate_add: field 'y2_m' is a number"},
      {"sim.on('lap_done', print)", "sim.on: unknown event 'lap_done'"},
      {"sim.on('wall_contact')", "sim.on(kind, handler): handler is a function"},
      {"sim.wait('soon')", "sim.wait(seconds): seconds is a number"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = WriteScenario(
        "return sim.scenario { name = 'helpers', run = function() end,\n"
        "  world = function()\n"
        "    " +
            cases[i].first + "\n  end }\n",
        std::to_string(i));
    EXPECT_EQ(WorldError(path), Shown(path) + ":3: " + cases[i].second + " (in world)");
  }
}

}  // namespace
}  // namespace unimouse
