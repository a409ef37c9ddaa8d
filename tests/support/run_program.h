// SPDX-License-Identifier: GPL-3.0-or-later
// Runs the built `unimouse` program as a user would and captures what it says.
#ifndef UNIMOUSE_TESTS_RUN_PROGRAM_H_
#define UNIMOUSE_TESTS_RUN_PROGRAM_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace unimouse::testing {

struct Outcome {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs a shell command, capturing its output and exit code.
Outcome Shell(const std::string& command);

/// Runs `unimouse <arguments>`, after environment assignments ("A=b ") if any. Every
/// result.json in the temporary directory is then collected for the schema check
/// (result_records.h).
Outcome Unimouse(const std::string& arguments, const std::string& environment = "");

struct RunResult {
  Outcome outcome;
  nlohmann::json result;  ///< its result.json; null when it wrote none
};

/// Runs `unimouse run <arguments>` with a fresh output directory `out_name` in the temporary
/// directory, and reads the result.json it wrote there; `environment` as for Unimouse.
RunResult UnimouseRun(const std::string& arguments, const std::string& out_name,
                      const std::string& environment = "");

/// Returns the lines of the first block of code (fenced by ```, or indented by four spaces or
/// more) after the first occurrence of `after` in the page `doc` (a path from the source tree,
/// e.g. "docs/robots.md"), as a user copies them: indentation removed, a line ending in a
/// backslash joined with the next. Empty when the page or the text is not there.
std::vector<std::string> DocumentedCommands(const std::string& doc, const std::string& after);

/// Runs a documented `unimouse ...` command word for word in `directory`, with the built program
/// in the place of `unimouse`. Result records are collected as Unimouse does.
Outcome RunDocumented(const std::string& command, const std::string& directory);

/// Whether xvfb-run is installed: tests that need a display skip without it.
bool HaveXvfbRun();

/// Whether the tests' python3 (UNIMOUSE_PYTHON3, Debian's first) starts: tests of Python
/// programs skip without it.
bool HavePython();

/// The `environment` for Unimouse that runs the program on a virtual X display of its own
/// (xvfb-run, a 1280x1024 screen). The display's authority file is kept in a fresh directory:
/// when xvfb-run keeps it in a directory of its own, it removes that as it exits, and when the
/// removal fails (as it once did with several displays starting at once) xvfb-run exits with 5
/// instead of the program's exit code.
std::string OnVirtualDisplay();

/// Makes a new, empty directory in the temporary directory, named after `stem` and unique to
/// this call, and returns its path.
std::string FreshDirectory(const std::string& stem);

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_RUN_PROGRAM_H_
