// SPDX-License-Identifier: GPL-3.0-or-later
// A run as a library object, in this process: scenarios decided, faults of MuJoCo turned into a
// result that says why, and a result.json that always belongs to the run that wrote it.
#include "session.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "probe_components.h"
#include "text_file.h"
#include "unimouse/errors.h"
#include "unimouse_protocol.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

class SessionTest : public ::testing::Test {
 protected:
  SessionTest() : registry_(testing::BundledComponents()) {
    registry_.AddStatic(ComponentType<testing::MujocoError>());
    options_.registry = &registry_;
    options_.out_dir = (fs::temp_directory_path() / "session").string();
    options_.only_asked_pictures = true;  // no picture: this is about the run
    options_.console = false;
  }

  RunRecord RunToTheEnd() {
    std::unique_ptr<Session> session = Session::Open(options_);
    while (!session->Over()) session->Step();
    return session->Finish();
  }

  nlohmann::json ResultFile() const {
    return nlohmann::json::parse(ReadTextFile(options_.out_dir + "/result.json"));
  }

  // a robot file in the scratch directory: the test rig with the given components
  std::string RobotFile(const std::string& components) const {
    const std::string path = (fs::temp_directory_path() / "robot.yaml").string();
    WriteTextFile(path, testing::RigYaml(0, components));
    return path;
  }

  PluginRegistry registry_;
  SessionOptions options_;
};

std::string Controller(const std::string& name) {
  return std::string(UNIMOUSE_SOURCE_DIR) + "/tests/scenarios/" + name;
}

TEST_F(SessionTest, AScenarioIsDecidedInThisProcess) {
  options_.scenario = "speed_control";
  options_.controller = Controller("speed_controller.lua");
  const RunRecord passed = RunToTheEnd();
  EXPECT_EQ(passed.exit_code, kExitPassed);
  EXPECT_EQ(passed.scenario->outcome.status, "passed");
  // the file holds the record as it was returned
  EXPECT_EQ(ResultFile(), RunRecordJson(passed));

  options_.controller = Controller("too_slow_controller.lua");
  const RunRecord failed = RunToTheEnd();
  EXPECT_EQ(failed.exit_code, kExitFailed);
  EXPECT_EQ(failed.scenario->outcome.status, "failed");
  EXPECT_NE(failed.scenario->outcome.reason.find("too slow"), std::string::npos)
      << failed.scenario->outcome.reason;
}

TEST_F(SessionTest, AMujocoErrorInAComponentsCallEndsTheRunWithExitCode3AndSaysWhy) {
  options_.robot = RobotFile(
      "  - { type: test.mujoco_error, name: boom, params: { at_step: 5, where: hook } }\n");
  options_.maze = "none";
  const RunRecord result = RunToTheEnd();
  EXPECT_EQ(result.exit_code, kExitRuntimeFault);
  EXPECT_EQ(result.status, "fault");
  EXPECT_EQ(result.steps, 5);
  const std::string error = ResultFile()["error"];
  EXPECT_NE(error.find("MuJoCo error"), std::string::npos) << error;
  EXPECT_NE(error.find("boom"), std::string::npos) << error;
}

TEST_F(SessionTest, AMujocoErrorInThePhysicsStepEndsTheRunWithExitCode3AndSaysWhy) {
  options_.robot = RobotFile(
      "  - { type: test.mujoco_error, name: boom, params: { at_step: 3, where: physics } }\n");
  options_.maze = "none";
  const RunRecord result = RunToTheEnd();
  EXPECT_EQ(result.exit_code, kExitRuntimeFault);
  const std::string error = ResultFile()["error"];
  EXPECT_EQ(error.rfind("MuJoCo error", 0), 0u) << error;
  EXPECT_EQ(result.steps, 3);
}

TEST_F(SessionTest, AResultFromAnEarlierRunNeverSurvivesAFailedStart) {
  fs::create_directories(options_.out_dir);
  WriteTextFile(options_.out_dir + "/result.json", R"({"status": "completed"})");
  options_.robot = (fs::temp_directory_path() / "no_such_robot.yaml").string();
  EXPECT_THROW(Session::Open(options_), InputError);
  const nlohmann::json result = ResultFile();
  EXPECT_EQ(result["status"], "error");
  EXPECT_EQ(result["exit_code"], kExitBadInput);
  EXPECT_NE(result["error"].get<std::string>().find("no_such_robot.yaml"), std::string::npos);
}

TEST_F(SessionTest, TheRecordSaysWhereTheWallTimeWentAndWhetherTheFirmwareSetThePace) {
  options_.maze = "none";
  options_.duration_s = 0.2;
  const RunRecord alone = RunToTheEnd();
  EXPECT_FALSE(alone.firmware_paced);
  EXPECT_EQ(alone.wall_time_split.firmware_s, 0.0);
  EXPECT_GT(alone.wall_time_split.physics_s, 0);

  options_.link = "native:" + std::string(UNIMOUSE_TEST_FIRMWARE);
  const RunRecord paced = RunToTheEnd();
  ASSERT_EQ(paced.exit_code, kExitPassed) << paced.error;
  EXPECT_TRUE(paced.firmware_paced);
  const TickTimes& split = paced.wall_time_split;
  EXPECT_GT(split.firmware_s, 0);
  EXPECT_LE(split.physics_s + split.components_s + split.firmware_s + split.scenario_s,
            paced.wall_time_s);
}

TEST_F(SessionTest, RealTimeIsAskedForEvenWhenTheFirmwareSetsThePace) {
  options_.maze = "none";
  options_.duration_s = 0.3;
  options_.link = "native:" + std::string(UNIMOUSE_TEST_FIRMWARE);
  options_.realtime = true;
  const RunRecord result = RunToTheEnd();
  ASSERT_EQ(result.exit_code, kExitPassed) << result.error;
  EXPECT_TRUE(result.firmware_paced);
  // 0.3 s of steps on the wall clock (unpaced, this firmware runs them in about 0.02 s)
  EXPECT_GT(result.wall_time_s, 0.25);
  EXPECT_TRUE(result.real_time_pacing.has_value());
}

// a TCP port free on this machine now (the system picks it), so that runs side by side do not
// meet on one
int FreePort() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof(a);
  EXPECT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
  EXPECT_EQ(::getsockname(s, reinterpret_cast<sockaddr*>(&a), &size), 0);
  ::close(s);
  return ntohs(a.sin_port);
}

// a board on Wi-Fi, as a lab has one: it dials the simulator's TCP server and commands both
// motors forward every 20 ms (with `also` after the commands) until told to stop
class TcpBoard {
 public:
  explicit TcpBoard(int port, std::vector<uint8_t> also = {})
      : thread_([this, port, also] {
          int s = -1;
          while (!stop_ && s < 0) {
            s = ::socket(AF_INET, SOCK_STREAM, 0);
            sockaddr_in a{};
            a.sin_family = AF_INET;
            a.sin_port = htons(static_cast<uint16_t>(port));
            a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            if (::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
              ::close(s);
              s = -1;
              std::this_thread::sleep_for(std::chrono::milliseconds(5));
            }
          }
          std::vector<uint8_t> f = {UNIMOUSE_ID_MOTOR_LEFT, 0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0};
          unimouse_put_u16(&f[1], 600);
          unimouse_put_u16(&f[4], 600);
          f.insert(f.end(), also.begin(), also.end());
          while (!stop_) {
            if (::write(s, f.data(), f.size()) != static_cast<ssize_t>(f.size())) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
          }
          if (s >= 0) ::close(s);
        }) {}
  ~TcpBoard() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_ = false;
  std::thread thread_;
};

TEST_F(SessionTest, ABoardLinkFromTheRobotFileIsPacedToTheWallClockLikeOneFromTheCommandLine) {
  // the same TCP link, once declared by the robot file and once given as --link: a board lives
  // in real time either way, so both runs take their simulated time on the wall clock
  options_.maze = "none";
  options_.duration_s = 1.5;
  const int port = FreePort();
  const std::string spec = "tcp:127.0.0.1:" + std::to_string(port);
  const std::string robot = (fs::temp_directory_path() / "tcp_robot.yaml").string();
  WriteTextFile(robot, testing::ReadBundledRobot() +
                           "  - { type: unimouse.link, name: link, params: { transport: '" + spec +
                           "' } }\n");
  for (const bool from_robot_file : {true, false}) {
    SCOPED_TRACE(from_robot_file ? "link in the robot file" : "--link");
    options_.robot = from_robot_file ? robot : "unimouse";
    options_.link = from_robot_file ? "" : spec;
    std::unique_ptr<Session> session = Session::Open(options_);
    RunRecord r;
    {
      const TcpBoard board(port);
      while (!session->Over()) session->Step();
      r = session->Finish();
    }
    ASSERT_EQ(r.exit_code, kExitPassed) << r.error;
    ASSERT_TRUE(r.real_time_pacing.has_value());
    // unpaced, this robot runs 1.5 s in well under 0.1 s of wall time
    EXPECT_GE(r.wall_time_s, 0.9 * 1.5);
    EXPECT_EQ(r.real_time_pacing->steps, 1500);
    // paced, every step is released on time: the run takes its simulated time within 10 %, and
    // the rest of the wall time is the run's start and end (a host too busy to keep up says so)
    if (!r.real_time_pacing->fell_behind) {
      EXPECT_LE(r.wall_time_s, 1.1 * 1.5 + 0.3);
    }
    // the board drove the robot forward (north)
    EXPECT_GT(r.robot().pose.y_m - 0.09, 0.05);
    ASSERT_TRUE(r.robot().driver.link.has_value());
    EXPECT_EQ(r.robot().driver.link->transport, "tcp");
  }
}

// a Lua file of the test's own in the scratch directory
std::string LuaFile(const std::string& name, const std::string& text) {
  const std::string path = (fs::temp_directory_path() / name).string();
  WriteTextFile(path, text);
  return path;
}

constexpr const char* kDrivenScenario =
    "return sim.scenario { name = 'driven', run = function() sim.wait(5) end }\n";

TEST_F(SessionTest, EveryFailureBeforeTheFirstStepLeavesAnErrorResultWithItsTraceback) {
  struct Case {
    std::string scenario, controller, error;
  };
  const std::string syntax = LuaFile("syntax.lua", "return sim.scenario { name = 'x' \n");
  const std::string world = LuaFile("world.lua",
                                    "return sim.scenario { name = 'x', run = function() end,\n"
                                    "  world = function() error('no floor') end }\n");
  const std::string table = LuaFile("table.lua", "return sim.scenario { name = 'x' }\n");
  const std::string driven = LuaFile("driven.lua", kDrivenScenario);
  const std::string controller = LuaFile("controller.lua", "local x = \nreturn 1\n");
  const std::vector<Case> cases = {
      {syntax, "", "syntax.lua:2: '}' expected (to close '{' at line 1) near <eof>"},
      {world, "", "world.lua:2: no floor (in world)"},
      {table, "", "sim.scenario needs a run function"},
      {driven, controller, "controller.lua:2: unexpected symbol near 'return'"},
  };
  for (const Case& c : cases) {
    options_.scenario = c.scenario;
    options_.controller = c.controller;
    fs::create_directories(options_.out_dir);
    WriteTextFile(options_.out_dir + "/result.json", R"({"status": "completed"})");
    EXPECT_THROW(Session::Open(options_), RuntimeFault) << c.scenario;
    const nlohmann::json result = ResultFile();
    EXPECT_EQ(result["status"], "error");
    EXPECT_EQ(result["exit_code"], kExitRuntimeFault);
    const std::string error = result["error"];
    EXPECT_NE(error.find(c.error), std::string::npos) << error;
    EXPECT_NE(result.value("traceback", "").find("stack traceback:"), std::string::npos)
        << result.dump();
  }
}

TEST_F(SessionTest, AControllerFaultEndsAsAFaultWithItsReasonNeverAsRunning) {
  options_.scenario = LuaFile("driven.lua", kDrivenScenario);
  options_.controller = LuaFile("faulty.lua",
                                "return function(time_s)\n"
                                "  if time_s > 0.05 then error('wheel fell off') end\n"
                                "end\n");
  const RunRecord result = RunToTheEnd();
  EXPECT_EQ(result.exit_code, kExitRuntimeFault);
  const nlohmann::json file = ResultFile();
  EXPECT_EQ(file["status"], "fault");
  EXPECT_EQ(file["scenario"]["status"], "error");
  const std::string reason = file["scenario"]["reason"];
  EXPECT_NE(reason.find("faulty.lua:2: wheel fell off (in the controller)"), std::string::npos)
      << reason;
}

TEST_F(SessionTest, SpendingMostOfTheBudgetAtEveryTickMeetsTheRunsAverage) {
  // 15 million instructions a tick, each call under its 20 million; the run allows 20 million
  // plus 100 million per simulated second: the second tick (at 1 ms) goes beyond it
  options_.scenario = LuaFile("busy.lua",
                              "return sim.scenario { name = 'busy', run = function()\n"
                              "  while true do\n"
                              "    for i = 1, 15e6 do end\n"
                              "    sim.next_tick()\n"
                              "  end\n"
                              "end }\n");
  options_.maze = "none";
  const RunRecord result = RunToTheEnd();
  EXPECT_EQ(result.exit_code, kExitRuntimeFault);
  EXPECT_EQ(result.steps, 1);
  const std::string error = result.error;
  EXPECT_NE(error.find("busy.lua:3: instruction budget exhausted: more than 100 million "
                       "instructions per simulated second on average (in run)"),
            std::string::npos)
      << error;
}

TEST_F(SessionTest, TextThatIsNotUtf8IsReplacedInTheResultNotFatal) {
  // a Latin-1 reason, HUD line and scenario name: each byte 0xe9 becomes U+FFFD
  options_.scenario = LuaFile("latin1.lua",
                              "return sim.scenario { name = 'caf\xe9', run = function()\n"
                              "  sim.hud_set(1, 'd\xe9j\xe0')\n"
                              "  sim.fail('trop lent \xe9')\n"
                              "end }\n");
  const RunRecord result = RunToTheEnd();
  EXPECT_EQ(result.exit_code, kExitFailed);
  const nlohmann::json file = ResultFile();
  EXPECT_EQ(file["scenario"]["name"], "caf\xef\xbf\xbd");
  EXPECT_EQ(file["scenario"]["reason"], "trop lent \xef\xbf\xbd");
  EXPECT_EQ(file["scenario"]["hud"][0], "d\xef\xbf\xbdj\xef\xbf\xbd");
}

TEST_F(SessionTest, AScriptErrorThatIsNotUtf8StillLeavesAResult) {
  options_.scenario = LuaFile("latin1_error.lua",
                              "error('\xe9"
                              "chec')\n");
  EXPECT_THROW(Session::Open(options_), RuntimeFault);
  const std::string error = ResultFile()["error"];
  EXPECT_NE(error.find("\xef\xbf\xbd"
                       "chec"),
            std::string::npos)
      << error;
}

TEST_F(SessionTest, OverAndStepAgreeWithTheDuration) {
  options_.maze = "none";
  options_.duration_s = 0.01;
  std::unique_ptr<Session> session = Session::Open(options_);
  int steps = 0;
  while (!session->Over()) {
    session->Step();
    ++steps;
  }
  EXPECT_EQ(steps, 10);
  session->Step();  // past the end: nothing happens
  EXPECT_EQ(session->kernel().state().step(), 10);
  EXPECT_EQ(session->Finish().steps, 10);
}

TEST_F(SessionTest, ARobotPressedAgainstAWallIsOneContactWithItsPlaceAndPart) {
  // straight north from japan2018's start, the first wall across column 0 is the north wall of
  // cell (0, 2) (`unimouse maze show japan2018`); the motors keep pushing into it for 4 s
  options_.maze = "japan2018";
  options_.duration_s = 6;
  options_.driven_by_caller = true;
  std::unique_ptr<Session> session = Session::Open(options_);
  Kernel& kernel = session->kernel();
  const int left = kernel.model().FindSignal("left.command");
  const int right = kernel.model().FindSignal("right.command");
  int touches_begun = 0;  // as MuJoCo reports them, step by step
  bool touching = false;
  while (!session->Over()) {
    kernel.state().signals()[left] = 150;
    kernel.state().signals()[right] = 150;
    session->Step();
    const bool now = kernel.world().RobotTouchesScenery(kernel.state().data());
    touches_begun += now && !touching;
    touching = now;
  }
  const RunRecord r = session->Finish();
  // the robot ends against that wall: its centre in cell (0, 2), its nose at the wall
  EXPECT_NEAR(r.robot().pose.y_m, 3 * 0.18 - 0.006, 0.08);
  // one contact, though the touch MuJoCo reports flickers as the motors push (18 times here)
  EXPECT_GT(touches_begun, 1);
  EXPECT_EQ(r.robot().wall_contacts, 1) << touches_begun << " touches began";
  ASSERT_EQ(r.contacts.size(), 1u);
  const Contact& c = r.contacts.front();
  ASSERT_TRUE(c.cell.has_value());
  EXPECT_EQ(c.cell->x, 0);
  EXPECT_EQ(c.cell->y, 2);
  EXPECT_EQ(c.side, 'N');
  // the wall's south face: three cells up, less half a wall's thickness
  EXPECT_NEAR(c.y_m, 3 * 0.18 - 0.006, 0.002);
  EXPECT_EQ(c.part, "plate");
  EXPECT_NE(ReadTextFile(options_.out_dir + "/log.txt")
                .find("contact: unimouse touched the N wall of cell (0, 2) with its plate"),
            std::string::npos);
  const nlohmann::json contact = ResultFile()["contacts"][0];
  EXPECT_EQ(contact["side"], "N");
  EXPECT_EQ(contact["cell"], nlohmann::json({0, 2}));
}

TEST_F(SessionTest, TheFirstTimeTheFirmwaresCellIsNotTheRobotsTheRunWarnsOnce) {
  // a board that says it visited a cell: next to the start cell, then far from it
  options_.maze = "japan2018";
  options_.duration_s = 0.5;
  const int port = FreePort();
  options_.link = "tcp:127.0.0.1:" + std::to_string(port);
  for (const int y : {1, 5}) {
    SCOPED_TRACE("the firmware reports cell (0, " + std::to_string(y) + ")");
    std::unique_ptr<Session> session = Session::Open(options_);
    RunRecord r;
    {
      const TcpBoard board(port, {UNIMOUSE_ID_DEBUG_VISITED, 0, static_cast<uint8_t>(y)});
      while (!session->Over()) session->Step();
      r = session->Finish();
    }
    ASSERT_EQ(r.exit_code, kExitPassed) << r.error;
    const std::string lost =
        "run: firmware reports cell (0, 5) but the robot is in cell (0, 0): it has lost its "
        "position";
    // within one cell is a report made as the robot crosses into the next: no warning
    const std::vector<std::string> expected =
        y == 5 ? std::vector{lost} : std::vector<std::string>{};
    EXPECT_EQ(r.warnings, expected);
  }
}

}  // namespace
}  // namespace unimouse
