// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as a batch manifest, read as `unimouse batch plan` reads it: a list of jobs or an
// InputError, nothing else. Reading starts nothing and writes nothing.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "manifest.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // the manifest names its files relative to its own directory: one of its own, with nothing in it
  static const std::string dir = [] {
    const auto d = std::filesystem::temp_directory_path() /
                   ("unimouse_fuzz_manifest_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d.string();
  }();
  static const std::string file = dir + "/manifest.yaml";
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    unimouse::batch::LoadManifest(file);
  } catch (const unimouse::InputError&) {
    // bad input is the expected answer to most bytes
  }
  return 0;
}
