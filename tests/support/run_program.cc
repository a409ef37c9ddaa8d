// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_program.h"

#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
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

std::vector<std::string> DocumentedCommands(const std::string& doc, const std::string& after) {
  const std::string page = ReadTextFile(std::string(UNIMOUSE_SOURCE_DIR) + "/" + doc);
  std::vector<std::string> commands;
  size_t at = page.find(after);
  if (at == std::string::npos) return commands;
  // the first block after it: a fenced one (```), or lines indented by four spaces or more
  enum class Block { kNone, kFenced, kIndented } block = Block::kNone;
  bool continued = false;
  for (at = page.find('\n', at); at != std::string::npos && at + 1 < page.size();) {
    const size_t end = std::min(page.find('\n', at + 1), page.size());
    std::string line = page.substr(at + 1, end - at - 1);
    at = end < page.size() ? end : std::string::npos;
    const size_t text = line.find_first_not_of(' ');
    const bool fence = text != std::string::npos && line.compare(text, 3, "```") == 0;
    if (block == Block::kNone) {
      if (fence) block = Block::kFenced;
      if (!fence && text != std::string::npos && text >= 4) block = Block::kIndented;
      if (block != Block::kIndented) continue;
    } else if (block == Block::kFenced ? fence : (text == std::string::npos || text < 4)) {
      break;
    }
    if (text == std::string::npos) continue;
    line = line.substr(text);
    const bool continues = !line.empty() && line.back() == '\\';
    if (continues) line.pop_back();
    if (continued) {
      commands.back() += line;
    } else {
      commands.push_back(line);
    }
    continued = continues;
  }
  return commands;
}

Outcome RunDocumented(const std::string& command, const std::string& directory) {
  const std::string word = "unimouse";
  if (command.compare(0, word.size(), word) != 0) return {-1, "not a unimouse command: " + command};
  const Outcome out =
      Shell("cd '" + directory + "' && " + UNIMOUSE_BINARY + command.substr(word.size()));
  CollectResultRecords(directory);
  return out;
}

std::string FreshDirectory(const std::string& stem) {
  std::string path =
      (std::filesystem::temp_directory_path() / ("unimouse_" + stem + "_XXXXXX")).string();
  if (::mkdtemp(path.data()) == nullptr) {
    throw std::runtime_error(path + ": cannot make a directory");
  }
  return path;
}

bool HavePython() { return std::system(UNIMOUSE_PYTHON3 " -c '' >/dev/null 2>&1") == 0; }

bool HaveXvfbRun() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

std::string OnVirtualDisplay() {
  return "xvfb-run -a -f " + FreshDirectory("xauth") + "/Xauthority -s '-screen 0 1280x1024x24' ";
}

}  // namespace unimouse::testing
