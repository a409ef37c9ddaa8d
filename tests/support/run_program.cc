// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_program.h"

#include <stdlib.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "result_records.h"
#include "text_file.h"

namespace unimouse::testing {

Outcome Shell(const std::string& command) {
  Outcome out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.output.append(buffer, n);
  const int status = pclose(pipe);
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

Outcome Unimouse(const std::string& arguments, const std::string& environment) {
  const Outcome out = Shell(environment + UNIMOUSE_BINARY + " " + arguments);
  // whatever result.json it wrote is checked against the schema, even if the test removes it
  CollectResultRecords(std::filesystem::temp_directory_path().string());
  return out;
}

RunResult UnimouseRun(const std::string& arguments, const std::string& out_name,
                      const std::string& environment) {
  const std::string out = (std::filesystem::temp_directory_path() / out_name).string();
  std::filesystem::remove_all(out);
  RunResult run{Unimouse("run --out " + out + " " + arguments, environment), nullptr};
  if (std::filesystem::exists(out + "/result.json")) {
    run.result = nlohmann::json::parse(ReadTextFile(out + "/result.json"));
  }
  return run;
}

std::string FreshDirectory(const std::string& stem) {
  std::string path =
      (std::filesystem::temp_directory_path() / ("unimouse_" + stem + "_XXXXXX")).string();
  if (::mkdtemp(path.data()) == nullptr) {
    throw std::runtime_error(path + ": cannot make a directory");
  }
  return path;
}

}  // namespace unimouse::testing
