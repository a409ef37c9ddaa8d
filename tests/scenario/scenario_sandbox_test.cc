// SPDX-License-Identifier: GPL-3.0-or-later
// Scenarios in this process, without a run: loading turns whatever a file returns into a clean
// one-line error, never a crash; each scenario has its own instruction budget, which no pcall
// can swallow, its memory limit and its allocation budget; work in C is counted or bounded, and
// a call stuck in C for good ends the process with exit code 3; errors in the prelude's helpers
// name the scenario's line. Under the sanitizer build (CMakePresets.json) these tests also show
// that no error skips a C++ destructor or unwinds through Lua.
#include <gtest/gtest.h>
#include <lua5.4/lua.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "scenario.h"
#include "scenario_api.h"
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
    "instruction budget exhausted: more than 20 million instructions in one call into the "
    "script, its limit per call (a loop that never waits? use sim.wait)";
constexpr const char* kMemoryFull = "not enough memory: a scenario holds at most 256 MiB";
constexpr const char* kAllocationsSpent =
    "allocation budget exhausted: more than 2048 MiB allocated between two waits (strings built "
    "in a loop?)";

// a scenario whose world runs `body`, a line each, from line 2 of the file
std::string WorldScenario(const std::string& body, const std::string& suffix = "") {
  return WriteScenario(
      "return sim.scenario { name = 'limits', run = function() end, world = function()\n" + body +
          "\nend }\n",
      suffix);
}

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

TEST(ScenarioLoadTest, AMazeThatCannotBeReadIsAScriptErrorNotAnExceptionThroughLua) {
  const std::string path = WorldScenario("  sim.maze_load('no_such_maze_anywhere')");
  const std::string error = WorldError(path);
  EXPECT_EQ(error.rfind(Shown(path) + ":2: ", 0), 0u) << error;
  EXPECT_NE(error.find("no_such_maze_anywhere"), std::string::npos) << error;
}

TEST(ScenarioMazeTest, AMazeIsBuiltAtItsContestsDimensionsUnlessTheScenarioNamesItsClass) {
  // 32 x 32: half-size by itself (90 mm cells, 6 mm walls, 25 mm high); 16 x 16: classic
  // unless said to be half-size
  const std::string path = WorldScenario(
      "  sim.maze_load('japan2016hef')\n"
      "  local d = sim.maze_get_dimensions()\n"
      "  assert(d.width == 32 and d.height == 32 and d.class == 'half', d.class)\n"
      "  assert(d.cell_m == 0.09 and d.wall_thickness_m == 0.006 and d.wall_height_m == 0.025)\n"
      "  sim.maze_load('UK-techfest-2022-a')\n"
      "  assert(sim.maze_get_dimensions().cell_m == 0.18)\n"
      "  sim.maze_load('UK-techfest-2022-a', { class = 'half' })\n"
      "  assert(sim.maze_get_dimensions().cell_m == 0.09)\n"
      "  sim.maze_load('japan2016hef', { class = 'classic' })\n"
      "  assert(sim.maze_get_dimensions().wall_height_m == 0.05)");
  EXPECT_EQ(WorldError(path), "");
}

TEST(ScenarioMazeTest, AMazeClassThatIsNoneOfTheThreeIsAScriptError) {
  const std::string path = WorldScenario("  sim.maze_load('japan2018', { class = 'mini' })");
  const std::string error = WorldError(path);
  EXPECT_NE(error.find("class is auto, classic or half, not 'mini'"), std::string::npos) << error;
}

TEST(ScenarioMemoryTest, AStringBeyondTheMemoryLimitIsAScriptError) {
  const std::string path = WorldScenario("  local s = string.rep('x', 1e9)");
  EXPECT_EQ(WorldError(path), std::string(kMemoryFull) + " (in world)");
}

TEST(ScenarioMemoryTest, ATableThatGrowsWithoutEndMeetsTheLimit) {
  const std::string path = WorldScenario(
      "  local kept = {}\n"
      "  for i = 1, 1e6 do kept[i] = string.rep('x', 1e6) .. i end");
  EXPECT_EQ(WorldError(path), std::string(kMemoryFull) + " (in world)");
}

TEST(ScenarioMemoryTest, TheHostsOwnCallsAreNeverRefusedMemory) {
  // memory filled to the limit by the script; sim.maze_get_start still makes its table, and
  // pcall hands the script its own memory error as a value
  const std::string path = WorldScenario(
      "  local kept, ok = {}, true\n"
      "  local function grow() kept[#kept + 1] = string.rep('x', 1e5) .. #kept end\n"
      "  while ok do ok = pcall(grow) end\n"
      "  local start = sim.maze_get_start()\n"
      "  assert(start.x == 0 and start.y == 0)\n"
      "  local ok2, why = pcall(string.rep, 'y', 1e8)\n"
      "  assert(not ok2 and why == 'not enough memory', why)");
  EXPECT_EQ(WorldError(path), "");
}

TEST(ScenarioMemoryTest, BuildingStringsInALoopSpendsTheAllocationBudget) {
  const std::string path = WorldScenario(
      "  local s = string.rep('x', 6e4)\n"
      "  while true do local t = s .. 'y' end");
  EXPECT_EQ(WorldError(path), std::string(kAllocationsSpent) + " (in world)");
}

TEST(ScenarioMemoryTest, APcallCannotSwallowTheSpentAllocationBudget) {
  const std::string path = WorldScenario(
      "  local s = string.rep('x', 6e4)\n"
      "  while true do pcall(function() local t = s .. 'y' end) end");
  EXPECT_EQ(WorldError(path), path + ":3: " + kAllocationsSpent + " (in world)");
}

TEST(ScenarioBudgetTest, ElementsMovedInsideTheLibraryCountAgainstTheBudget) {
  // without the count, one call moves 10^12 nils in C and the hook never runs
  const std::string path = WorldScenario("  table.move({}, 1, 1e12, 2)");
  EXPECT_EQ(WorldError(path), path + ":2: " + kBudgetSpent + " (in world)");
}

TEST(ScenarioBudgetTest, ShiftingAndSortingTablesCountAgainstTheBudget) {
  const std::string path = WorldScenario(
      "  local t = {}\n"
      "  for i = 1, 1e5 do t[i] = i end\n"
      "  while true do table.insert(t, 1, 0); table.remove(t, 1); table.sort(t) end");
  EXPECT_EQ(WorldError(path), path + ":4: " + kBudgetSpent + " (in world)");
}

TEST(ScenarioBudgetTest, EmptyCopiesAreMadeAtOnceAndTheLibraryStillWorks) {
  // string.rep('', n) used to loop n times in C
  const std::string path = WorldScenario(
      "  assert(string.rep('', 1e15) == '' and (''):rep(math.maxinteger, '') == '')\n"
      "  assert(string.rep('ab', 3, ',') == 'ab,ab,ab')\n"
      "  local t = { 3, 1, 2 }\n"
      "  table.sort(t); table.insert(t, 1, 0); table.insert(t, 9); table.remove(t, 2)\n"
      "  assert(table.concat(t, ' ') == '0 2 3 9', table.concat(t, ' '))\n"
      "  assert(table.concat(table.move({ 1, 2, 3 }, 1, 3, 2), ' ') == '1 1 2 3')");
  EXPECT_EQ(WorldError(path), "");
}

TEST(ScenarioPreludeTest, ErrorsOfTheCountedLibraryFunctionsNameTheScenariosLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"string.rep({}, 2)", "bad argument #1 to 'string.rep' (string expected, got table)"},
      {"('x'):rep(2, {})", "bad argument #3 to 'string.rep' (string expected, got table)"},
      {"table.insert(nil, 1, 2)", "bad argument #1 to 'table.insert' (table expected, got nil)"},
      {"table.insert({}, 5, 2)", "bad argument #2 to 'table.insert' (position out of bounds)"},
      {"table.remove({}, 'a')", "bad argument #2 to 'table.remove' (number expected, got string)"},
      {"table.move({}, 1, 'x', 2)",
       "bad argument #3 to 'table.move' (number expected, got string)"},
      {"setmetatable(1, {})", "bad argument #1 to 'setmetatable' (table expected, got number)"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = WorldScenario("  " + cases[i].first, std::to_string(i));
    EXPECT_EQ(WorldError(path), Shown(path) + ":2: " + cases[i].second + " (in world)");
  }
}

TEST(ScenarioBudgetTest, AFinalizerWhichNoBudgetCouldStopIsRefused) {
  const std::string path =
      WorldScenario("  setmetatable({}, { __gc = function() while true do end end })");
  EXPECT_EQ(WorldError(path), Shown(path) +
                                  ":2: setmetatable: __gc (a finalizer) is not available to "
                                  "scenarios (in world)");
}

TEST(ScenarioBudgetTest, APatternThatBacktracksCountsItsStepsAgainstTheBudget) {
  // without the count, the matcher runs in C for hours and the hook never runs
  const std::string path = WorldScenario(
      "  local s = string.rep('a', 1e5)\n"
      "  for _ in s:gmatch('.-.-.-.-.-b') do end");
  EXPECT_EQ(WorldError(path), path + ":3: " + kBudgetSpent + " (in world)");
  const std::string find = WorldScenario("  ('a'):rep(1e5):find('.-.-.-.-.-b')", "_find");
  EXPECT_EQ(WorldError(find), find + ":2: " + kBudgetSpent + " (in world)");
}

TEST(ScenarioPreludeTest, PatternFunctionsBehaveAsLuasOwn) {
  // expected values worked out from the Lua 5.4 manual
  const std::string path = WorldScenario(R"lua(
  local function same(a, b) assert(a == b, tostring(a) .. ' ~= ' .. tostring(b)) end
  local function list(...) return table.concat({ ... }, ',') end
  same(list(('hello world'):find('o w')), '5,7')
  same(list(('hello'):find('(h)(e)')), '1,2,h,e')
  same(list(('a.b'):find('.', 1, true)), '2,2')
  same(list(('a.b'):find('b', -1)), '3,3')
  same(('abc'):find('x'), nil)
  same(('abc'):find('a', 10), nil)
  same(list(('key = value'):match('(%w+)%s*=%s*(%w+)')), 'key,value')
  same(list(('hello'):match('()ll()')), '3,5')
  same(('  x  '):match('^%s*(.-)%s*$'), 'x')
  same(list(('hello world'):gsub('o', '0')), 'hell0 w0rld,2')
  same(list(('abc'):gsub('', '-')), '-a-b-c-,4')
  same(list(('abc'):gsub('x*', '-')), '-a-b-c-,4')
  same(list(('hello world'):gsub('(%w+)', '<%1>')), '<hello> <world>,2')
  same(list(('abc'):gsub('%w', '%0%0')), 'aabbcc,3')
  same(list(('abc'):gsub('%w', '%%')), '%%%,3')
  same(list(('$name is $age'):gsub('%$(%w+)', { name = 'x', age = 3 })), 'x is 3,2')
  same(list(('abc'):gsub('b', function() return false end)), 'abc,1')
  same(list(('abc'):gsub('(b)()', function(b, at) return b:upper() .. at end)), 'aB3c,1')
  same(list(('aaa'):gsub('a', 'b', 2)), 'bba,2')
  same(list(('hello hello'):gsub('^h', 'H')), 'Hello hello,1')
  local words = {}
  for w in ('one two  three'):gmatch('%a+') do words[#words + 1] = w end
  same(table.concat(words, ','), 'one,two,three')
  local pairs_found = {}
  for k, v in ('a=1, b=2'):gmatch('(%w+)=(%w+)') do pairs_found[#pairs_found + 1] = k .. v end
  same(table.concat(pairs_found, ','), 'a1,b2')
  local empties = 0
  for e in ('abc'):gmatch('x*') do empties = empties + 1 end
  same(empties, 4)
  local from_two = {}
  for c in ('abc'):gmatch('.', 2) do from_two[#from_two + 1] = c end
  same(table.concat(from_two), 'bc'))lua");
  EXPECT_EQ(WorldError(path), "");
}

TEST(ScenarioPreludeTest, PatternErrorsNameTheScenariosLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"('a'):find('[a')", "malformed pattern (missing ']')"},
      {"('a'):match('%')", "malformed pattern (ends with '%')"},
      {"string.find(nil, 'a')", "bad argument #1 to 'string.find' (string expected, got nil)"},
      {"('a'):gsub('a', '%2')", "invalid capture index %2 in replacement string"},
      {"('a'):gsub('a', '%x')", "invalid use of '%' in replacement string"},
      {"('a'):gsub('a', {}, 'x')",
       "bad argument #4 to 'string.gsub' (number expected, got string)"},
      {"('a'):gsub('a')",
       "bad argument #3 to 'string.gsub' (string/function/table expected, got "
       "no value)"},
      {"('a'):gsub('a', function() return {} end)", "invalid replacement value (a table)"},
      {"string.gmatch({}, 'a')", "bad argument #1 to 'string.gmatch' (string expected, got table)"},
      {"for _ in ('a'):gmatch('(') do end", "unfinished capture"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string path = WorldScenario("  " + cases[i].first, std::to_string(i));
    EXPECT_EQ(WorldError(path), Shown(path) + ":2: " + cases[i].second + " (in world)");
  }
}

TEST(ScenarioWatchdogTest, ACallStuckInCEndsTheProcessWithExitCode3) {
  // comparing two long equal strings is one instruction of 60 million bytes: the count sees
  // almost nothing, the wall clock everything
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::string path = WorldScenario(
      "  local a, b = string.rep('x', 6e7), string.rep('x', 6e7)\n"
      "  while true do local same = a == b end");
  EXPECT_EXIT(
      {
        const auto s = Scenario::Load(path, {}, 1);
        s->SetWatchdog(0.5, [](const std::string& why) {
          std::fprintf(stderr, "expired: %s\n", why.c_str());
        });
        s->BuildWorld();
      },
      ::testing::ExitedWithCode(kExitRuntimeFault),
      "expired: the scenario's world ran longer than 0.5 s of wall time in one call");
}

TEST(ScenarioRandomTest, TheWholeRangeOfIntegersIsDrawnWithoutOverflow) {
  // the largest interval is 2^64 integers wide; draws must spread over it
  const std::string path = WorldScenario(
      "  local low, high, negative = 0, 0, 0\n"
      "  for i = 1, 64 do\n"
      "    local x = math.random(math.mininteger, math.maxinteger)\n"
      "    assert(math.type(x) == 'integer')\n"
      "    if x < 0 then negative = negative + 1 end\n"
      "    local y = math.random(math.maxinteger - 1, math.maxinteger)\n"
      "    assert(y == math.maxinteger - 1 or y == math.maxinteger, y)\n"
      "    if y == math.maxinteger then high = high + 1 else low = low + 1 end\n"
      "  end\n"
      "  assert(negative > 8 and negative < 56, negative)\n"
      "  assert(low > 8 and high > 8, low .. ' ' .. high)\n"
      "  local seen = {}\n"
      "  for i = 1, 200 do local z = math.random(-3, 3); seen[z] = true end\n"
      "  for z = -3, 3 do assert(seen[z], z) end\n"
      "  assert(seen[-4] == nil and seen[4] == nil)");
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

// the bad input loading the file and building its world gives; "" when there is none
std::string WorldInputError(const std::string& path) {
  try {
    Scenario::Load(path, {}, 1)->BuildWorld();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioKeysTest, ATypoInAnOptionalKeyIsNamedWithItsCorrectionAtTheScenariosLine) {
  // without the check the robot would face north, yaw_deg's default, and nothing would say so
  const std::string path = WorldScenario("sim.robot_place { x_m = 0, y_m = 0, yaw = 0 }");
  EXPECT_EQ(WorldInputError(path), Shown(path) +
                                       ":2: unknown key yaw in sim.robot_place, did you mean "
                                       "yaw_deg? (in world)");
}

TEST(ScenarioKeysTest, EveryFunctionThatTakesATableRefusesAnUnknownKey) {
  // from the API's own list, so that a new function cannot be left out; by hand: scenario,
  // wait_until, robot_place, wall_add, wall_arc, wall_polyline, box_add, snapshot_save, gate_add,
  // maze_load
  int tables = 0;
  for (const ApiEntry& e : ScenarioApiEntries()) {
    const TableArgument table = TableArgumentOf(e);
    if (table.position == 0) continue;
    ++tables;
    // the table in its place, the arguments before it nil: the keys are checked first
    std::string arguments;
    for (int i = 1; i < table.position; ++i) arguments += "nil, ";
    const std::string misspelt = table.keys.front() + "_x";
    const std::string path = WorldScenario(
        "sim." + std::string(e.name) + "(" + arguments + "{ " + misspelt + " = 1 })", e.name);
    EXPECT_EQ(WorldInputError(path), Shown(path) + ":2: unknown key " + misspelt + " in sim." +
                                         e.name + ", did you mean " + table.keys.front() +
                                         "? (in world)");
  }
  EXPECT_EQ(tables, 10);
}

TEST(ScenarioKeysTest, TheKeysAreTheNamesTheSignatureShows) {
  const auto entry = [](std::string_view name) {
    for (const ApiEntry& e : ScenarioApiEntries()) {
      if (name == e.name) return TableArgumentOf(e);
    }
    return TableArgument{-1, {}};
  };
  EXPECT_EQ(entry("robot_place").position, 1);
  EXPECT_EQ(entry("robot_place").keys,
            (std::vector<std::string>{"x_m", "y_m", "yaw_deg", "robot"}));
  EXPECT_EQ(entry("snapshot_save").position, 2);
  EXPECT_EQ(entry("snapshot_save").keys, (std::vector<std::string>{"camera", "width", "height"}));
  EXPECT_EQ(entry("wall_polyline").keys,
            (std::vector<std::string>{"points", "thickness_m", "height_m"}));
  EXPECT_EQ(entry("box_add").keys, (std::vector<std::string>{"x_m", "y_m", "size_m", "yaw_deg"}));
  EXPECT_EQ(entry("hud_set").position, 0);
  EXPECT_EQ(entry("time").position, 0);
}

TEST(ScenarioKeysTest, AKeyFarFromEveryNameListsTheNames) {
  const std::string path = WorldScenario("sim.wall_add { 0, 0, 1, 1 }");
  EXPECT_EQ(WorldInputError(path),
            Shown(path) +
                ":2: unknown key 1 in sim.wall_add (its keys: x1_m, y1_m, x2_m, y2_m, "
                "thickness_m, height_m) (in world)");
}

TEST(ScenarioKeysTest, AnUnknownKeyOfTheScenarioTableIsBadInputWhileLoading) {
  const std::string path = WriteScenario(
      "return sim.scenario { name = 'typo', run = function() end,\n"
      "  paramz = { laps = 3 } }\n");
  try {
    Scenario::Load(path, {}, 1);
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    // the tail call leaves no frame with a line: the key's own line is named
    EXPECT_EQ(std::string(e.what()),
              path + ":2: unknown key paramz in sim.scenario, did you mean params?");
  }
}

TEST(ScenarioKeysTest, TheKeysTheSignatureNamesAreTaken) {
  const std::string path = WorldScenario(
      "sim.robot_place { x_m = 0, y_m = 0, yaw_deg = 0 }\n"
      "sim.wall_arc { cx_m = 0, cy_m = 0, radius_m = 1, from_deg = 0, to_deg = 90, segments = 3,\n"
      "               thickness_m = 0.01, height_m = 0.05 }\n"
      "sim.box_add { x_m = 1, y_m = 1, size_m = { 0.1, 0.1, 0.1 }, yaw_deg = 10 }");
  EXPECT_EQ(WorldInputError(path), "");
  EXPECT_EQ(WorldError(path), "");
}

}  // namespace
}  // namespace unimouse
