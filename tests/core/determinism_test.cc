// SPDX-License-Identifier: GPL-3.0-or-later
// Same inputs and seed, same run, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "inline_assets.h"
#include "kernel.h"
#include "probe_components.h"

namespace unimouse {
namespace {

class DeterminismTest : public ::testing::Test {
 protected:
  void SetUp() override {
    registry_.AddStatic(ComponentType<testing::RandomTorque>());
    robot_ = ParseRobotSpec(testing::BundledRobotWith(
                                "  - { type: test.random_torque, name: drive, params: { scale_nm: "
                                "0.003 } }\n")
                                .text,
                            "robot.yaml");
    maze_ = std::make_unique<Maze>(ParseMazeText(testing::kSmallMaze, "small.txt"));
  }

  // final qpos after a random walk that bumps into the maze's walls
  std::vector<mjtNum> FinalQpos(uint64_t seed, Kernel* reuse = nullptr) {
    std::unique_ptr<Kernel> fresh;
    Kernel* k = reuse;
    if (k == nullptr) {
      fresh = Kernel::Create(robot_, maze_.get(), registry_, seed);
      k = fresh.get();
    }
    for (int i = 0; i < 3000; ++i) k->Step();
    const mjData& d = k->state().data();
    return std::vector<mjtNum>(d.qpos, d.qpos + k->mj_model().nq);
  }

  PluginRegistry registry_;
  RobotSpec robot_;
  std::unique_ptr<Maze> maze_;
};

bool BitIdentical(const std::vector<mjtNum>& a, const std::vector<mjtNum>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(mjtNum)) == 0;
}

TEST_F(DeterminismTest, SameSeedGivesBitIdenticalFinalQpos) {
  const std::vector<mjtNum> first = FinalQpos(7);
  const std::vector<mjtNum> second = FinalQpos(7);
  EXPECT_TRUE(BitIdentical(first, second));
}

TEST_F(DeterminismTest, DifferentSeedGivesADifferentRun) {
  EXPECT_FALSE(BitIdentical(FinalQpos(7), FinalQpos(8)));
}

TEST_F(DeterminismTest, ResetReplaysTheRunExactly) {
  auto kernel = Kernel::Create(robot_, maze_.get(), registry_, 7);
  const std::vector<mjtNum> first = FinalQpos(7, kernel.get());
  const uint64_t hash = kernel->state().Hash();
  kernel->Reset();
  const std::vector<mjtNum> second = FinalQpos(7, kernel.get());
  EXPECT_TRUE(BitIdentical(first, second));
  EXPECT_EQ(kernel->state().Hash(), hash);
}

TEST_F(DeterminismTest, CopiedStateContinuesIdentically) {
  auto kernel = Kernel::Create(robot_, maze_.get(), registry_, 7);
  for (int i = 0; i < 500; ++i) kernel->Step();
  State saved(kernel->mj_model(), static_cast<int>(kernel->state().component_state().size()),
              static_cast<int>(kernel->state().signals().size()));
  saved.CopyFrom(kernel->state());
  for (int i = 0; i < 500; ++i) kernel->Step();
  const uint64_t straight = kernel->state().Hash();
  kernel->state().CopyFrom(saved);
  for (int i = 0; i < 500; ++i) kernel->Step();
  EXPECT_EQ(kernel->state().Hash(), straight);
}

}  // namespace
}  // namespace unimouse
