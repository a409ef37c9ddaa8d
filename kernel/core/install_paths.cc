// SPDX-License-Identifier: GPL-3.0-or-later
#include "install_paths.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

fs::path ExecutableDirectory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::current_path() : exe.parent_path();
}

}  // namespace

std::string PluginDirectory() {
  return (ExecutableDirectory() / UNIMOUSE_BIN_TO_PLUGINS).lexically_normal().string();
}

std::string DataDirectory() {
  return (ExecutableDirectory() / UNIMOUSE_BIN_TO_DATA).lexically_normal().string();
}

std::string FirmwareDirectory() {
  return (ExecutableDirectory() / UNIMOUSE_BIN_TO_FIRMWARE).lexically_normal().string();
}

std::string FirmwareCMakeDirectory() {
  return (ExecutableDirectory() / UNIMOUSE_BIN_TO_FIRMWARE_CMAKE).lexically_normal().string();
}

std::string ResolveDataFile(const std::string& name, const std::string& folder,
                            const std::string& extension) {
  if (IsRegularFile(name)) return name;
  const fs::path bundled = fs::path(DataDirectory()) / folder / (name + extension);
  if (name.find('/') == std::string::npos && IsRegularFile(bundled)) {
    return bundled.string();
  }
  throw InputError(name + ": no such file, and no bundled " + folder.substr(0, folder.size() - 1) +
                   " of that name in " + (fs::path(DataDirectory()) / folder).string());
}

}  // namespace unimouse
