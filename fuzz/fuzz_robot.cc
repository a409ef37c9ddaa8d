// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as a robot file, checked as `unimouse check` does: parsed, its world built and its
// components created and bound, never started. A robot or an InputError, nothing else.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "bundled_components.h"
#include "kernel.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const unimouse::PluginRegistry registry = [] {
    unimouse::PluginRegistry r;
    unimouse::AddBundledComponents(r);
    return r;
  }();
  static const std::string out =
      (std::filesystem::temp_directory_path() / ("unimouse_fuzz_" + std::to_string(::getpid())))
          .string();
  try {
    const unimouse::RobotSpec robot =
        unimouse::ParseRobotSpec(std::string(reinterpret_cast<const char*>(data), size), "f.yaml");
    unimouse::KernelOptions options;
    options.output_dir = out;
    options.start_components = false;
    options.log_sink = [](double, int, const std::string&, const std::string&) {};
    unimouse::Kernel::Create(robot, nullptr, registry, options);
  } catch (const unimouse::InputError&) {
    // bad input is the expected answer to most bytes
  }
  return 0;
}
