// SPDX-License-Identifier: GPL-3.0-or-later
#include "result_records.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>
#include <utility>

#include "text_file.h"

namespace unimouse::testing {
namespace {

namespace fs = std::filesystem;

// the name of the test that runs, or of the last one when none does
std::string& TestName() {
  static std::string name = "no_test";
  return name;
}

// what was copied already: place and content
std::set<std::pair<std::string, size_t>>& Copied() {
  static std::set<std::pair<std::string, size_t>> copied;
  return copied;
}

// a file name made of the test's name and the record's place
std::string CopyName(const fs::path& relative, int number) {
  std::string place = relative.string();
  for (char& c : place) {
    if (c == '/') c = '_';
  }
  if (place.size() > 120) place = place.substr(place.size() - 120);
  return TestName() + "__" + place + "__" + std::to_string(::getpid()) + "_" +
         std::to_string(number) + ".json";
}

// after each test: the runs it made in this process, before the next test can overwrite them
class CollectAfterEachTest : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo& test) override {
    // a file name: a parameterised test's name has a '/'
    TestName() = std::string(test.test_suite_name()) + "." + test.name();
    std::replace(TestName().begin(), TestName().end(), '/', '.');
  }
  void OnTestEnd(const ::testing::TestInfo&) override {
    CollectResultRecords(fs::temp_directory_path().string());
  }
};

[[maybe_unused]] const bool registered = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new CollectAfterEachTest);
  return true;
}();

}  // namespace

int CollectResultRecords(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(UNIMOUSE_RESULT_RECORDS_DIR, ec);
  int copied = 0;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->path().filename() != "result.json" || !it->is_regular_file(ec)) continue;
    std::string content;
    try {
      content = ReadTextFile(it->path().string());
    } catch (const std::exception&) {
      continue;  // gone since the listing: a run that is being replaced
    }
    const auto key = std::make_pair(it->path().string(), std::hash<std::string>{}(content));
    if (!Copied().insert(key).second) continue;
    const fs::path copy =
        fs::path(UNIMOUSE_RESULT_RECORDS_DIR) /
        CopyName(fs::relative(it->path(), dir), static_cast<int>(Copied().size()));
    WriteTextFile(copy.string(), content);
    ++copied;
  }
  return copied;
}

}  // namespace unimouse::testing
