// SPDX-License-Identifier: GPL-3.0-or-later
#include "crc32.h"

#include <array>

namespace unimouse {
namespace {

constexpr std::array<uint32_t, 256> MakeTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int bit = 0; bit < 8; ++bit) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

constexpr std::array<uint32_t, 256> kTable = MakeTable();

}  // namespace

// the register starts and ends inverted, so a running CRC is resumed by inverting it back
uint32_t Crc32(uint32_t crc, std::string_view bytes) {
  uint32_t c = ~crc;
  for (char byte : bytes) c = kTable[(c ^ static_cast<uint8_t>(byte)) & 0xFFu] ^ (c >> 8);
  return ~c;
}

}  // namespace unimouse
