// SPDX-License-Identifier: GPL-3.0-or-later
#include "text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "unimouse/errors.h"

namespace unimouse {

bool IsRegularFile(const std::string& path) noexcept {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

bool IsDirectory(const std::string& path) noexcept {
  std::error_code error;
  return std::filesystem::is_directory(path, error);
}

bool PathExists(const std::string& path) noexcept {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

std::string ReadTextFile(const std::string& path) {
  if (IsDirectory(path)) {
    throw InputError(path + ": is a directory, not a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in.good()) {
    throw InputError(path + ": cannot open file (" + std::strerror(errno) + ")");
  }
  // read in pieces and stop past the limit: a huge file (or an endless one, /dev/zero) is
  // never read whole
  std::string text;
  char piece[1 << 16];
  while (text.size() <= kMaxInputFile_bytes && in.read(piece, sizeof(piece)).gcount() > 0) {
    text.append(piece, static_cast<size_t>(in.gcount()));
  }
  if (text.size() > kMaxInputFile_bytes) {
    throw InputError(path + ": larger than " + std::to_string(kMaxInputFile_bytes >> 20) +
                     " MiB, more than any input unimouse reads (docs/limits.md)");
  }
  return text;
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

std::string XmlEscaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' ? ' ' : c;
    }
  }
  return out;
}

}  // namespace unimouse
