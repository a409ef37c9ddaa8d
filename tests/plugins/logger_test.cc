// SPDX-License-Identifier: GPL-3.0-or-later
// The trace logger writes every period's ground truth and signals, and every logged text line
// with its sim time, as CSV or JSON lines, and keeps them when the run ends.
#include "logger.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "probe_components.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> Lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class LoggerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("unimouse_logger_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    registry_ = testing::BundledComponents();
    registry_.AddStatic(ComponentType<testing::Talker>());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // runs the bundled robot with a talker and a logger for `steps`, driving both wheels
  void RunRobot(const std::string& logger_params, int steps, bool start = true) {
    const std::string components =
        testing::ReadBundledRobot().substr(testing::ReadBundledRobot().find("\ncomponents:\n") +
                                           13) +
        "  - { type: test.talker, name: firmware, params: { text: ping } }\n"
        "  - { type: unimouse.logger, name: log, params: { " +
        logger_params + " } }\n";
    KernelOptions options;
    options.output_dir = dir_.string();
    options.start_components = start;
    auto kernel =
        Kernel::Create(ParseRobotSpec(testing::BundledRobotWith(components).text, "robot.yaml"),
                       nullptr, registry_, options);
    kernel->state().signals()[kernel->model().FindSignal("left.command")] = 800;
    kernel->state().signals()[kernel->model().FindSignal("right.command")] = 800;
    for (int i = 0; i < steps; ++i) kernel->Step();
    kernel->Finish();
  }

  fs::path dir_;
  PluginRegistry registry_;
};

TEST_F(LoggerTest, CsvHasAHeaderAndOneRowPerPeriod) {
  RunRobot("path: mine.csv, joints: left_wheel, signals: 'left.current_a, left.encoder_counts'",
           100);
  const std::vector<std::string> lines = Lines(dir_ / "mine.csv");
  ASSERT_EQ(lines.size(), 1u + 10u);  // a row every 10 ms over 100 ms
  EXPECT_EQ(lines[0],
            "time_s,x_m,y_m,yaw_rad,speed_m_per_s,yaw_rate_rad_per_s,left_wheel_rad_per_s,"
            "left.current_a,left.encoder_counts");
  EXPECT_EQ(lines[1].rfind("0,0,0,", 0), 0u) << lines[1];  // at rest at the origin at t = 0
  // the last row: t = 0.09 s, moving forward (north) with current flowing
  std::stringstream row(lines.back());
  std::vector<double> v;
  for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::stod(cell));
  ASSERT_EQ(v.size(), 9u);
  EXPECT_NEAR(v[0], 0.09, 1e-12);
  EXPECT_GT(v[2], 0);
  EXPECT_GT(v[4], 0);
  EXPECT_GT(v[6], 0);
  EXPECT_GT(v[7], 0);
}

TEST_F(LoggerTest, CsvKeepsTextLinesWithTheirSimTimeInASiblingFile) {
  RunRobot("path: runs/a.csv", 30);
  const std::vector<std::string> lines = Lines(dir_ / "runs" / "a_messages.csv");
  ASSERT_EQ(lines.size(), 1u + 30u);  // every line the talker logged, none lost
  EXPECT_EQ(lines[0], "time_s,level,source,text");
  EXPECT_EQ(lines[1], "0,info,\"firmware\",\"ping 0\"");
  EXPECT_EQ(lines[30], "0.029000000000000019,info,\"firmware\",\"ping 29\"");
}

TEST_F(LoggerTest, JsonLinesInterleaveRowsAndTextLines) {
  RunRobot("path: trace.jsonl, format: jsonl, signals: tof.front_m", 20);
  const std::vector<std::string> lines = Lines(dir_ / "trace.jsonl");
  int rows = 0, texts = 0;
  for (const auto& line : lines) {
    const nlohmann::json j = nlohmann::json::parse(line);
    if (j.contains("text")) {
      ++texts;
      EXPECT_EQ(j["source"], "firmware");
    } else {
      ++rows;
      EXPECT_TRUE(j.contains("tof.front_m"));
      EXPECT_TRUE(j.contains("yaw_rad"));
    }
  }
  EXPECT_EQ(rows, 2);
  EXPECT_EQ(texts, 20);  // every line, also those logged after its last period
}

TEST_F(LoggerTest, UnwritablePathIsABadInput) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "taken") << "a file, not a directory";
  try {
    RunRobot("path: taken/trace.csv", 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write the log"), std::string::npos) << e.what();
  }
}

TEST_F(LoggerTest, APathOutsideTheOutputDirectoryIsRefusedWithItsLine) {
  const fs::path outside = dir_.parent_path() / "escaped.csv";
  for (const std::string& path :
       {outside.string(), std::string("../escaped.csv"), std::string("logs/../../escaped.csv")}) {
    try {
      RunRobot("path: '" + path + "'", 1);
      ADD_FAILURE() << path;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("robot.yaml:", 0), 0u) << what;
      EXPECT_NE(what.find("output directory"), std::string::npos) << what;
    }
    EXPECT_FALSE(fs::exists(outside)) << path;
  }
}

TEST_F(LoggerTest, ALoggerThatIsOnlyCheckedWritesNothing) {
  RunRobot("path: logs/trace.csv", 20, /*start=*/false);
  EXPECT_FALSE(fs::exists(dir_));
}

}  // namespace
}  // namespace unimouse
