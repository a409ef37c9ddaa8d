// SPDX-License-Identifier: GPL-3.0-or-later
// The examples built for an Arduino Mega 2560 (arduino-lib/avr): each one linked, and its flash
// and RAM within the ATmega2560's 256 KiB and 8 KiB, as avr-size reports them.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "text_file.h"

namespace unimouse {
namespace {

TEST(AvrBuildTest, EveryExampleFitsTheAtmega2560) {
  const std::string dir = UNIMOUSE_BINARY_DIR "/avr";
  if (!std::filesystem::exists(dir)) {
    GTEST_SKIP() << "no AVR build: gcc-avr and arduino-core-avr are not installed";
  }
  for (const char* example : {"micromouse", "speed_control", "time_trial", "wall_distance"}) {
    const std::string size_file = dir + "/" + example + ".size.txt";
    ASSERT_TRUE(std::filesystem::exists(size_file)) << size_file;
    const std::string report = ReadTextFile(size_file);
    std::smatch program, data;
    ASSERT_TRUE(std::regex_search(report, program, std::regex("Program: +([0-9]+) bytes")))
        << report;
    ASSERT_TRUE(std::regex_search(report, data, std::regex("Data: +([0-9]+) bytes"))) << report;
    EXPECT_LT(std::stoi(program[1]), 256 * 1024) << example;
    EXPECT_LT(std::stoi(data[1]), 8 * 1024) << example;
    EXPECT_GT(std::stoi(data[1]), 0) << example;
  }
}

}  // namespace
}  // namespace unimouse
