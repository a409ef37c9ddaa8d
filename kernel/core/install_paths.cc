// SPDX-License-Identifier: GPL-3.0-or-later
#include "install_paths.h"

#include <algorithm>
#include <filesystem>
#include <utility>

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

std::string ResolveBundledFirmware(const std::string& link_spec) {
  static const std::pair<const char*, const char*> kinds[] = {
      {"native:", ""}, {"inproc:", ".so"}, {"avr:", ".elf"}};
  for (const auto& [prefix, extension] : kinds) {
    if (link_spec.rfind(prefix, 0) != 0) continue;
    // the program is the first word; a native program's arguments follow it
    const std::size_t start = std::string(prefix).size();
    const std::size_t end = std::min(link_spec.find(' ', start), link_spec.size());
    const std::string name = link_spec.substr(start, end - start);
    if (name.empty() || name.find('/') != std::string::npos || fs::is_regular_file(name)) {
      return link_spec;
    }
    const fs::path bundled = fs::path(FirmwareDirectory()) / (name + extension);
    if (!fs::is_regular_file(bundled)) return link_spec;
    return prefix + bundled.string() + link_spec.substr(end);
  }
  return link_spec;
}

std::string ResolveDataFile(const std::string& name, const std::string& folder,
                            const std::string& extension) {
  if (fs::is_regular_file(name)) return name;
  const fs::path bundled = fs::path(DataDirectory()) / folder / (name + extension);
  if (name.find('/') == std::string::npos && fs::is_regular_file(bundled)) {
    return bundled.string();
  }
  throw InputError(name + ": no such file, and no bundled " + folder.substr(0, folder.size() - 1) +
                   " of that name in " + (fs::path(DataDirectory()) / folder).string());
}

}  // namespace unimouse
