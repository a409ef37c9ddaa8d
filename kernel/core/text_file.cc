// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "unimouse/errors.h"

namespace unimouse {

std::string ReadTextFile(const std::string& path) {
  if (std::filesystem::is_directory(path)) {
    throw InputError(path + ": is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in.good()) {
    throw InputError(path + ": cannot open file (" + std::strerror(errno) + ")");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteTextFile(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out.good()) {
      throw InputError(path + ": cannot write file (" + std::strerror(errno) + ")");
    }
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace unimouse
