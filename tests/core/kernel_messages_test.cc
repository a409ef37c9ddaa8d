// SPDX-License-Identifier: GPL-3.0-or-later
// What components log is bounded: each message is cut to a length, log lines to a volume and
// warnings to a number per run, and what was held back is counted when the run finishes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "inline_assets.h"
#include "kernel.h"
#include "probe_components.h"

namespace unimouse {
namespace {

class KernelMessagesTest : public ::testing::Test {
 protected:
  // a kernel with one talker logging `text` every step; what reaches the sink is kept
  std::unique_ptr<Kernel> Make(const std::string& text) {
    registry_.AddStatic(ComponentType<testing::Talker>());
    KernelOptions options;
    options.log_sink = [this](double, int, const std::string& source, const std::string& m) {
      if (source == "talker") seen_.push_back(m);
    };
    const RobotSpec robot = ParseRobotSpec(
        testing::BundledRobotWith("  - { type: test.talker, name: talker, params: { text: '" +
                                  text + "' } }\n")
            .text,
        "robot.yaml");
    return Kernel::Create(robot, nullptr, registry_, options);
  }

  PluginRegistry registry_;
  std::vector<std::string> seen_;
};

TEST_F(KernelMessagesTest, ALongMessageIsCutSayingHowLongItWas) {
  auto kernel = Make(std::string(5000, 'x'));
  kernel->Step();
  ASSERT_EQ(seen_.size(), 1u);
  // 5000 characters, a space and the step number "0"
  EXPECT_EQ(seen_[0], std::string(1000, 'x') + "... (5002 bytes in all)");
}

TEST_F(KernelMessagesTest, LogLinesBeyondAMebibyteAreCountedNotShown) {
  // 998 characters, a space and a step number below 10000: 1000 to 1003 bytes a line
  auto kernel = Make(std::string(998, 'y'));
  const int steps = 1200;
  for (int i = 0; i < steps; ++i) kernel->Step();
  kernel->Finish();
  // lines 0-9 take 1000 bytes, 10-99 1001, 100-999 1002 (1001890 in all), then 1003 each: 46
  // more fit in 1 MiB (1048576)
  const int shown = 1046;
  ASSERT_EQ(seen_.size(), static_cast<size_t>(shown + 2));
  EXPECT_EQ(seen_[shown], "more than 1 MiB of log lines: later ones are counted, not shown");
  EXPECT_EQ(seen_.back(), std::to_string(steps - shown) + " more messages were not shown");
}

TEST_F(KernelMessagesTest, AResetStartsTheBudgetAgain) {
  auto kernel = Make(std::string(998, 'z'));
  for (int i = 0; i < 1100; ++i) kernel->Step();
  kernel->Reset();
  seen_.clear();
  kernel->Step();
  EXPECT_EQ(seen_.size(), 1u);
}

}  // namespace
}  // namespace unimouse
