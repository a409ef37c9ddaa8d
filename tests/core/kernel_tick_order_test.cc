// SPDX-License-Identifier: GPL-3.0-or-later
// The tick of DESIGN.md: boundary hook, mj_step1, every Sense, every Actuate, mj_step2.
#include <gtest/gtest.h>

#include <algorithm>

#include "inline_assets.h"
#include "kernel.h"
#include "probe_components.h"

namespace unimouse {
namespace {

using testing::BundledRobotWith;
using testing::ProbeEvents;

class TickOrderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ProbeEvents().clear();
    registry_.AddStatic(ComponentType<testing::Probe>());
    // MuJoCo calls the control callback at the end of mj_step1
    mjcb_control = [](const mjModel*, mjData*) { ProbeEvents().push_back("mj_step1"); };
  }
  void TearDown() override { mjcb_control = nullptr; }

  std::unique_ptr<Kernel> Make(const std::string& components) {
    const RobotSpec robot = ParseRobotSpec(BundledRobotWith(components).text, "robot.yaml");
    return Kernel::Create(robot, nullptr, registry_, 1);
  }

  PluginRegistry registry_;
};

TEST_F(TickOrderTest, SensesAllComponentsAfterStep1ThenActuatesAllInYamlOrder) {
  auto kernel = Make(
      "  - { type: test.probe, name: a, params: { tag: a } }\n"
      "  - { type: test.probe, name: b, params: { tag: b } }\n");
  kernel->SetBoundaryHook([] { ProbeEvents().push_back("boundary"); });
  ProbeEvents().clear();
  kernel->Step();

  std::vector<std::string> hooks;
  for (const auto& e : ProbeEvents()) {
    if (e.rfind("x=", 0) != 0) hooks.push_back(e);
  }
  EXPECT_EQ(hooks, (std::vector<std::string>{"boundary", "mj_step1", "sense:a", "sense:b",
                                             "actuate:a", "actuate:b"}));
}

TEST_F(TickOrderTest, SenseSeesKinematicsOfWhatTheBoundaryHookChanged) {
  auto kernel = Make("  - { type: test.probe, name: a, params: { tag: a } }\n");
  Kernel* k = kernel.get();
  // a scenario teleports the robot at the tick boundary
  kernel->SetBoundaryHook([k] {
    Pose2D pose = k->world().spawn();
    pose.x_m = 0.5;
    k->world().PlaceRobot(k->state().data(), pose);
  });
  ProbeEvents().clear();
  kernel->Step();
  const auto& e = ProbeEvents();
  EXPECT_NE(std::find(e.begin(), e.end(), "x=" + std::to_string(0.5)), e.end());
}

TEST_F(TickOrderTest, ControlsWrittenInActuateActInTheSameStep) {
  auto kernel = Make("  - { type: test.probe, name: a, params: { tag: a, torque_nm: 0.001 } }\n");
  const int wheel = mj_name2id(&kernel->mj_model(), mjOBJ_JOINT, "left_wheel");
  const int dof = kernel->mj_model().jnt_dofadr[wheel];
  ASSERT_EQ(kernel->state().data().qvel[dof], 0);
  kernel->Step();
  // if mj_step2 ran before Actuate the wheel would still be at rest after one step
  EXPECT_GT(kernel->state().data().qvel[dof], 0);
  EXPECT_DOUBLE_EQ(kernel->state().data().time, kernel->timestep_s());
}

TEST_F(TickOrderTest, ComponentsRunEveryNStepsOfTheirPeriod) {
  auto kernel = Make(
      "  - { type: test.probe, name: fast, params: { tag: fast } }\n"
      "  - { type: test.probe, name: slow, period_s: 0.003, params: { tag: slow } }\n");
  ProbeEvents().clear();
  for (int i = 0; i < 7; ++i) kernel->Step();
  int fast = 0, slow = 0;
  for (const auto& e : ProbeEvents()) {
    fast += e == "sense:fast";
    slow += e == "sense:slow";
  }
  EXPECT_EQ(fast, 7);
  EXPECT_EQ(slow, 3);  // steps 0, 3 and 6
}

TEST_F(TickOrderTest, RejectsAPeriodThatIsNotAWholeNumberOfSteps) {
  try {
    Make("  - { type: test.probe, name: odd, period_s: 0.0025, params: { tag: odd } }\n");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("robot.yaml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a whole number of 0.001 s"), std::string::npos)
        << e.what();
  }
}

TEST_F(TickOrderTest, ResetRunsEveryComponentsResetAndRewindsTime) {
  auto kernel = Make("  - { type: test.probe, name: a, params: { tag: a } }\n");
  for (int i = 0; i < 5; ++i) kernel->Step();
  ProbeEvents().clear();
  kernel->Reset();
  const auto& e = ProbeEvents();
  EXPECT_EQ(std::count(e.begin(), e.end(), "reset:a"), 1);
  EXPECT_EQ(std::count(e.begin(), e.end(), "sense:a"), 0);
  EXPECT_EQ(kernel->state().step(), 0);
  EXPECT_EQ(kernel->state().data().time, 0);
  EXPECT_EQ(kernel->state().component_state()[0], 0);
}

}  // namespace
}  // namespace unimouse
