// SPDX-License-Identifier: GPL-3.0-or-later
// Runs the built `unimouse` program as a user would and captures what it says.
#ifndef UNIMOUSE_TESTS_RUN_PROGRAM_H_
#define UNIMOUSE_TESTS_RUN_PROGRAM_H_

#include <string>

namespace unimouse::testing {

struct Outcome {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `unimouse <arguments>`, after environment assignments ("A=b ") if any.
Outcome Unimouse(const std::string& arguments, const std::string& environment = "");

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_RUN_PROGRAM_H_
