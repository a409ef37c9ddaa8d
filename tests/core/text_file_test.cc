// SPDX-License-Identifier: GPL-3.0-or-later
// Input files are read whole up to a limit; a larger or endless one is refused without being
// read to its end.
#include "text_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

TEST(TextFileTest, AFileAtTheLimitIsReadWhole) {
  const std::string path = testing::FreshDirectory("text_file") + "/at_limit.txt";
  std::ofstream(path) << std::string(kMaxInputFile_bytes, 'x');
  EXPECT_EQ(ReadTextFile(path).size(), kMaxInputFile_bytes);
}

TEST(TextFileTest, AFileBeyondTheLimitIsRefusedNamingIt) {
  const std::string path = testing::FreshDirectory("text_file") + "/beyond.txt";
  std::ofstream(path) << std::string(kMaxInputFile_bytes + 1, 'x');
  try {
    ReadTextFile(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path +
                                         ": larger than 16 MiB, more than any input unimouse "
                                         "reads (docs/limits.md)");
  }
}

TEST(TextFileTest, AnEndlessFileIsRefused) { EXPECT_THROW(ReadTextFile("/dev/zero"), InputError); }

}  // namespace
}  // namespace unimouse
