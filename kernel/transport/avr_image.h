// SPDX-License-Identifier: GPL-3.0-or-later
// An AVR firmware image (.elf) checked completely before the emulator reads it: the ELF header,
// every program and section header, the string and symbol tables and simavr's .mmcu section are
// bounds-checked from the file's bytes alone, and then the sizes and addresses against the part's
// memories, so that simavr's own reader, which trusts all of them, only ever sees an image that it
// can read.
#ifndef UNIMOUSE_TRANSPORT_AVR_IMAGE_H_
#define UNIMOUSE_TRANSPORT_AVR_IMAGE_H_

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace unimouse::link {

/// Largest image file read: the biggest part's flash is 256 KiB, and debug information rarely
/// takes more than a few MiB.
inline constexpr uint64_t kMaxAvrImage_bytes = 16u << 20;
/// Most symbols an image may hold: simavr sorts them one insertion at a time.
inline constexpr uint32_t kMaxAvrImageSymbols = 16384;
/// Most sections and program headers an image may hold.
inline constexpr uint32_t kMaxAvrImageHeaders = 4096;

/// What a checked image holds, as simavr will read it.
struct AvrImage {
  struct Segment {
    uint32_t address = 0;       ///< where it runs (p_vaddr)
    uint32_t load_address = 0;  ///< where its bytes are kept (p_paddr)
    uint32_t file_bytes = 0;
    uint32_t memory_bytes = 0;
  };
  struct Symbol {
    std::string name;
    uint32_t value = 0;
    uint32_t size = 0;
    bool function = false;
  };

  std::string mcu;          ///< the part its .mmcu section names, or ""
  uint32_t f_cpu_hz = 0;    ///< the clock its .mmcu section names, or 0
  uint32_t flash_base = 0;  ///< where simavr puts .text: the value of __vectors
  uint32_t text_bytes = 0;
  uint32_t data_bytes = 0;    ///< .data, copied to flash after .text
  uint32_t data_address = 0;  ///< .data's address in the data space (0x800000 + RAM address)
  uint32_t bss_bytes = 0;
  uint32_t bss_address = 0;
  uint32_t eeprom_bytes = 0;
  uint32_t fuse_bytes = 0;
  uint32_t lock_bytes = 0;
  uint16_t command_register = 0;  ///< simavr's command and console registers, 0 for none
  uint16_t console_register = 0;
  std::vector<Segment> segments;  ///< the loadable ones (PT_LOAD)
  std::vector<Symbol> symbols;
};

/// The memories of the emulated part an image is to run on.
struct AvrMemory {
  std::string mcu;
  uint32_t flash_bytes = 0;
  uint32_t ram_start = 0;  ///< first SRAM address, after the I/O registers
  uint32_t ram_end = 0;    ///< last SRAM address (RAMEND)
  uint32_t eeprom_bytes = 0;
  uint32_t fuse_bytes = 0;
};

/// Checks the bytes of an image and returns what it holds. Throws InputError
/// "path: <one sentence naming what is wrong>".
AvrImage ParseAvrImage(std::span<const uint8_t> bytes, const std::string& path);
/// Reads the file (at most kMaxAvrImage_bytes) and checks it as ParseAvrImage does.
AvrImage ReadAvrImage(const std::string& path);
/// Throws InputError unless every size and address of the image lies within the part's memories.
void CheckAvrImageFits(const AvrImage& image, const AvrMemory& memory, const std::string& path);

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_AVR_IMAGE_H_
