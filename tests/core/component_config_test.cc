// SPDX-License-Identifier: GPL-3.0-or-later
// Component parameters are checked against the type's declared table before the component is
// created; bind-time names are checked against the model.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "inline_assets.h"
#include "kernel.h"
#include "probe_components.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using testing::BundledRobotWith;

class ComponentConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    registry_.AddStatic(ComponentType<testing::Probe>());
    registry_.AddStatic(ComponentType<testing::SignalRelay>());
  }

  // builds the bundled robot with these component lines and returns the error
  std::string ErrorOf(const std::string& components) {
    const testing::RobotYaml yaml = BundledRobotWith(components);
    line_ = yaml.first_component_line;
    first_ = components.substr(0, components.find('\n'));
    try {
      const RobotSpec robot = ParseRobotSpec(yaml.text, "robot.yaml");
      Kernel::Create(robot, nullptr, registry_, 1);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }

  // "robot.yaml:L:C: " where `token` starts on the first component line of the last ErrorOf
  std::string At(const std::string& token) const {
    return "robot.yaml:" + std::to_string(line_) + ":" + std::to_string(first_.find(token) + 1) +
           ": ";
  }

  PluginRegistry registry_;
  int line_ = 0;
  std::string first_;
};

TEST_F(ComponentConfigTest, AcceptsValidParametersAndFillsDefaults) {
  EXPECT_EQ(ErrorOf("  - { type: test.probe, name: p, params: { tag: x, count: 3 } }\n"),
            "no error");
}

TEST_F(ComponentConfigTest, UnknownParameterSuggestsTheNearestDeclaredOne) {
  const std::string e =
      ErrorOf("  - { type: test.probe, name: p, params: { tag: x, torque: 1 } }\n");
  EXPECT_EQ(e, At("torque") +
                   "component 'p' (test.probe): unknown parameter 'torque' (did you mean "
                   "'torque_nm'?)");
}

TEST_F(ComponentConfigTest, MissingRequiredParameterIsNamedWithItsMeaning) {
  std::string e = ErrorOf("  - { type: test.probe, name: p, params: { count: 2 } }\n");
  EXPECT_EQ(e, At("{ count") +
                   "component 'p' (test.probe): missing parameter 'tag' (name "
                   "written into the event log)");
  e = ErrorOf("  - { type: test.probe, name: p }\n");
  EXPECT_EQ(e, At("{ type") +
                   "component 'p' (test.probe): missing parameter 'tag' (name "
                   "written into the event log)");
}

TEST_F(ComponentConfigTest, WrongKindsOfValueAreRefused) {
  std::string e = ErrorOf("  - { type: test.probe, name: p, params: { tag: x, count: many } }\n");
  EXPECT_EQ(e, At("many") + "component 'p' (test.probe): count must be a number, not 'many'");
  e = ErrorOf("  - { type: test.probe, name: p, params: { tag: x, count: 2.5 } }\n");
  EXPECT_EQ(e, At("2.5") + "component 'p' (test.probe): count must be a whole number, not '2.5'");
  e = ErrorOf("  - { type: test.probe, name: p, params: { tag: x, enabled: yes } }\n");
  EXPECT_EQ(e, At("yes") + "component 'p' (test.probe): enabled must be true or false");
  e = ErrorOf("  - { type: test.probe, name: p, params: { tag: [x] } }\n");
  EXPECT_EQ(e, At("[x]") + "component 'p' (test.probe): tag must be a word or text");
}

TEST_F(ComponentConfigTest, NonFiniteAndOutOfRangeValuesAreRefused) {
  std::string e =
      ErrorOf("  - { type: test.probe, name: p, params: { tag: x, torque_nm: .nan } }\n");
  EXPECT_EQ(e, At(".nan") + "component 'p' (test.probe): torque_nm must be finite, not '.nan'");
  e = ErrorOf("  - { type: test.probe, name: p, params: { tag: x, count: 11 } }\n");
  EXPECT_EQ(e, At("11") + "component 'p' (test.probe): count must be within [1, 10], not 11");
  e = ErrorOf("  - { type: test.probe, name: p, params: { tag: x, mode: c } }\n");
  EXPECT_EQ(e, At("c }") + "component 'p' (test.probe): mode must be one of a|b, not 'c'");
}

TEST_F(ComponentConfigTest, UnknownTypeSuggestsAKnownOne) {
  const std::string e = ErrorOf("  - { type: test.prob, name: p }\n");
  EXPECT_EQ(e, At("{ type") +
                   "component 'p': unknown type 'test.prob' (did you mean "
                   "'test.probe'?); `unimouse plugins` lists the types found");
}

TEST_F(ComponentConfigTest, SignalsNeedExactlyOneWriter) {
  std::string e = ErrorOf("  - { type: test.relay, name: r, params: { read: speed } }\n");
  EXPECT_EQ(e, At("{ type") + "component 'r' reads signal 'speed', which no component writes");
  e = ErrorOf(
      "  - { type: test.relay, name: a, params: { write: speed } }\n"
      "  - { type: test.relay, name: b, params: { write: speed } }\n");
  EXPECT_EQ(e, "robot.yaml:" + std::to_string(line_ + 1) +
                   ":5: component 'b' (test.relay): signal 'speed' is already written by "
                   "component 'a'; a signal has one writer");
}

TEST_F(ComponentConfigTest, SignalsPassFromWriterToReader) {
  const RobotSpec robot = ParseRobotSpec(
      BundledRobotWith("  - { type: test.relay, name: a, params: { write: one } }\n"
                       "  - { type: test.relay, name: b, params: { read: one, write: two } }\n")
          .text,
      "robot.yaml");
  auto kernel = Kernel::Create(robot, nullptr, registry_, 1);
  kernel->Step();
  EXPECT_EQ(kernel->state().signals()[kernel->model().FindSignal("one")], 1);
  EXPECT_EQ(kernel->state().signals()[kernel->model().FindSignal("two")], 2);
}

TEST_F(ComponentConfigTest, AReaderBeforeItsWriterIsDeclaredAndSeesThePreviousTick) {
  const RobotSpec robot = ParseRobotSpec(
      BundledRobotWith("  - { type: test.relay, name: b, params: { read: one, write: two } }\n"
                       "  - { type: test.relay, name: a, params: { write: one } }\n")
          .text,
      "robot.yaml");
  auto kernel = Kernel::Create(robot, nullptr, registry_, 1);
  const Model& model = kernel->model();
  std::vector<std::string> early;
  for (const EarlyRead& e : model.early_reads) {
    early.push_back(model.components[e.reader].name + " < " + model.components[e.writer].name +
                    ": " + model.signal_names[e.signal]);
  }
  EXPECT_NE(std::find(early.begin(), early.end(), "b < a: one"), early.end());
  EXPECT_EQ(std::find(early.begin(), early.end(), "a < b: two"), early.end());
  kernel->Step();
  EXPECT_EQ(kernel->state().signals()[model.FindSignal("two")], 1);  // one was still 0
  kernel->Step();
  EXPECT_EQ(kernel->state().signals()[model.FindSignal("two")], 2);
}

TEST(ComponentBindTest, NamesResolvedAtBindTimeMustExistInTheModel) {
  PluginRegistry registry;
  registry.AddStatic(ComponentType<testing::Probe>());
  const RobotSpec robot = ParseRobotSpec(
      testing::TinyRobotWith("  - { type: test.probe, name: p, params: { tag: x } }\n"),
      "robot.yaml");
  try {
    Kernel::Create(robot, nullptr, registry, 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "robot.yaml:6:5: component 'p' (test.probe): no actuator named 'left_motor' "
                 "(the robot has: none)");
  }
}

}  // namespace
}  // namespace unimouse
