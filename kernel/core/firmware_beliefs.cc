// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware_beliefs.h"

#include <cstdio>
#include <sstream>

namespace unimouse {
namespace {

uint8_t SideBits(const std::string& names) {
  uint8_t bits = 0;
  std::istringstream in(names);
  std::string name;
  while (in >> name) {
    if (name == "N") bits |= 1;
    if (name == "E") bits |= 2;
    if (name == "S") bits |= 4;
    if (name == "W") bits |= 8;
  }
  return bits;
}

}  // namespace

bool FirmwareBeliefs::Read(const std::string& line) {
  int x = 0, y = 0, used = 0;
  if (std::sscanf(line.c_str(), "debug walls (%d, %d): %n", &x, &y, &used) == 2 && used > 0) {
    const std::string rest = line.substr(static_cast<size_t>(used));
    const size_t known = rest.find("; known ");
    if (known == std::string::npos) return false;
    walls[{x, y}] = {SideBits(rest.substr(0, known)), SideBits(rest.substr(known + 8))};
    return true;
  }
  if (std::sscanf(line.c_str(), "debug visited (%d, %d)", &x, &y) == 2) {
    visited.push_back({x, y});
    return true;
  }
  if (line.rfind("debug path", 0) == 0) {
    path.clear();
    const char* p = line.c_str() + 10;
    while (std::sscanf(p, " (%d, %d)%n", &x, &y, &used) == 2) {
      path.push_back({x, y});
      p += used;
    }
    return true;
  }
  return false;
}

}  // namespace unimouse
