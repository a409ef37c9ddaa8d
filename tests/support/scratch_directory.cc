// SPDX-License-Identifier: GPL-3.0-or-later
// Every test process works in a temporary directory of its own: TMPDIR points into it from the
// start, so std::filesystem::temp_directory_path() and the programs the tests start (which
// inherit it) never share a path with another test running at the same time, and nothing is
// left behind.
#include <stdlib.h>

#include <filesystem>
#include <string>

namespace {

class ScratchDirectory {
 public:
  ScratchDirectory() {
    const char* parent = std::getenv("TMPDIR");
    std::string pattern =
        std::string(parent != nullptr && *parent ? parent : "/tmp") + "/unimouse-tests-XXXXXX";
    if (::mkdtemp(pattern.data()) != nullptr) {
      path_ = pattern;
      ::setenv("TMPDIR", path_.c_str(), 1);
    }
  }
  ~ScratchDirectory() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }

 private:
  std::string path_;
};

const ScratchDirectory scratch;

}  // namespace
