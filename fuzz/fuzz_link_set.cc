// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as the `--link-set name=value` options of a run, one a line, on one of the link's
// transports (the first byte chooses): the bundled robot with that link is built and bound as
// `unimouse check` does, never started. A robot or an InputError, nothing else.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bundled_components.h"
#include "kernel.h"
#include "session.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const unimouse::PluginRegistry registry = [] {
    unimouse::PluginRegistry r;
    unimouse::AddBundledComponents(r);
    return r;
  }();
  static const unimouse::RobotSpec robot = unimouse::LoadRobotSpec(UNIMOUSE_FUZZ_ROBOT);
  static const std::string out =
      (std::filesystem::temp_directory_path() / ("unimouse_fuzz_" + std::to_string(::getpid())))
          .string();
  static const char* const kTransports[] = {"pty", "tcp::5555", "serial:/dev/null@115200",
                                            "avr:/nonexistent.elf", "native:/bin/true"};
  const std::string transport = kTransports[data[0] % std::size(kTransports)];
  std::vector<std::string> sets;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    sets.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  try {
    unimouse::RobotSpec with_link = robot;
    with_link.components.push_back(unimouse::LinkComponent(transport, "", sets));
    unimouse::KernelOptions options;
    options.output_dir = out;
    options.start_components = false;
    options.log_sink = [](double, int, const std::string&, const std::string&) {};
    unimouse::Kernel::Create(with_link, nullptr, registry, options);
  } catch (const unimouse::InputError&) {
    // bad input is the expected answer to most bytes
  }
  return 0;
}
