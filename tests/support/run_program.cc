// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_program.h"

#include <sys/wait.h>

#include <cstdio>

namespace unimouse::testing {

Outcome Unimouse(const std::string& arguments, const std::string& environment) {
  const std::string command = environment + UNIMOUSE_BINARY + " " + arguments + " 2>&1";
  Outcome out;
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.output.append(buffer, n);
  const int status = pclose(pipe);
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

}  // namespace unimouse::testing
