// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as a scenario: loaded, and its world built. A scenario, an InputError or a
// RuntimeFault (the script's own error), nothing else.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "scenario.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // Scenario::Load reads a file: one per process, rewritten for each input
  static const std::string path = (std::filesystem::temp_directory_path() /
                                   ("unimouse_fuzz_" + std::to_string(::getpid()) + ".lua"))
                                      .string();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    auto scenario = unimouse::Scenario::Load(path, {}, 1);
    scenario->BuildWorld();
  } catch (const unimouse::InputError&) {
  } catch (const unimouse::RuntimeFault&) {
    // a script error is the script's answer
  }
  return 0;
}
