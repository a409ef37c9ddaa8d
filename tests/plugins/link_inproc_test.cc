// SPDX-License-Identifier: GPL-3.0-or-later
// The in-process link: a firmware module loaded into the simulator drives the robot exactly as
// the same sketch built as a program does; a module that crashes, hangs, calls exit() or abort()
// ends the run with exit code 3 and says so in result.json; a module cannot be loaded twice at
// once.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

const std::string kFirmwareDir = UNIMOUSE_FIRMWARE_DIR;
const std::string kTestDir = UNIMOUSE_TEST_BINARY_DIR;

std::unique_ptr<Kernel> Make(const std::string& transport, const Maze* maze) {
  const std::string yaml = testing::ReadBundledRobot() +
                           "  - { type: unimouse.link, name: link, params: { transport: '" +
                           transport + "' } }\n";
  KernelOptions options;
  options.trust_robot_file = true;  // the test wrote the robot file
  options.seed = 5;
  return testing::MakeKernel(yaml, maze, options);
}

std::vector<mjtNum> Drive(Kernel& kernel, int steps) {
  for (int i = 0; i < steps; ++i) kernel.Step();
  const mjData& d = kernel.state().data();
  return {d.qpos, d.qpos + kernel.mj_model().nq};
}

TEST(InprocLinkTest, AModuleDrivesTheRobotAsItsProgramDoesAndCanBeLoadedAgain) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  auto native = Make("native:" + kFirmwareDir + "/micromouse", &maze);
  const std::vector<mjtNum> expected = Drive(*native, 3000);
  native.reset();
  for (int run = 0; run < 2; ++run) {
    // the second run loads the module afresh: its globals start over
    auto inproc = Make("inproc:" + kFirmwareDir + "/micromouse.so", &maze);
    const std::vector<mjtNum> q = Drive(*inproc, 3000);
    ASSERT_EQ(q.size(), expected.size());
    EXPECT_EQ(std::memcmp(q.data(), expected.data(), q.size() * sizeof(mjtNum)), 0) << run;
  }
}

TEST(InprocLinkTest, OneModuleRunsTwiceAtOnceEachCopyWithGlobalsOfItsOwn) {
  // two robots with the same firmware: the second loads a copy of the module, and the two,
  // stepped in turns, each drive exactly as the program alone does
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  auto native = Make("native:" + kFirmwareDir + "/micromouse", &maze);
  const std::vector<mjtNum> expected = Drive(*native, 2000);
  native.reset();
  auto first = Make("inproc:" + kFirmwareDir + "/micromouse.so", &maze);
  auto second = Make("inproc:" + kFirmwareDir + "/micromouse.so", &maze);
  for (int step = 0; step < 2000; step += 100) {
    Drive(*first, 100);
    Drive(*second, 100);
  }
  for (Kernel* k : {first.get(), second.get()}) {
    const mjData& d = k->state().data();
    ASSERT_EQ(static_cast<size_t>(k->mj_model().nq), expected.size());
    EXPECT_EQ(std::memcmp(d.qpos, expected.data(), expected.size() * sizeof(mjtNum)), 0);
  }
}

// `unimouse run` with a failing test firmware: exit code 3, and result.json's error
void ExpectFirmwareError(const std::string& module, const std::string& error) {
  const testing::RunResult r = testing::UnimouseRun(
      "--maze none --duration 1 --no-pictures --link inproc:" + kTestDir + "/" + module, module);
  EXPECT_EQ(r.outcome.exit_code, 3) << r.outcome.output;
  ASSERT_TRUE(r.result.is_object()) << r.outcome.output;
  EXPECT_EQ(r.result["status"], "fault");
  EXPECT_NE(r.result["error"].get<std::string>().find(error), std::string::npos)
      << r.result["error"];
}

TEST(InprocLinkTest, AFirmwareThatDereferencesNullEndsTheRunWithExitCode3) {
  ExpectFirmwareError("null_pointer_firmware.so",
                      "the firmware crashed: SIGSEGV (null pointer? address");
  ExpectFirmwareError("null_pointer_firmware.so", "at t=0.200 s");
}

TEST(InprocLinkTest, AFirmwareThatNeverReturnsFromLoopEndsTheRunWithExitCode3) {
  ExpectFirmwareError("hang_firmware.so",
                      "the firmware did not finish its step within 5 s at t=0.200 s");
}

TEST(InprocLinkTest, AFirmwareThatCallsExitEndsTheRunWithExitCode3) {
  ExpectFirmwareError("exit_firmware.so", "the firmware called exit(3) at t=0.200 s");
}

TEST(InprocLinkTest, AFirmwareThatCallsAbortEndsTheRunWithExitCode3) {
  ExpectFirmwareError("abort_firmware.so", "the firmware crashed: SIGABRT (abort()");
  ExpectFirmwareError("abort_firmware.so", "at t=0.200 s");
}

}  // namespace
}  // namespace unimouse
