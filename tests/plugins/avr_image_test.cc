// SPDX-License-Identifier: GPL-3.0-or-later
// AVR images checked before simavr reads them: the small firmwares of tests/avr, each damaged in
// one known place, are refused with a sentence naming that place, also those that crashed
// simavr's reader; a part's memories bound the sizes and addresses.
#include "avr_image.h"

#include <elf.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "avr_board.h"
#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

std::vector<uint8_t> Firmware(const std::string& name) {
#ifdef UNIMOUSE_AVR_TEST_FIRMWARE_DIR
  std::ifstream in(std::string(UNIMOUSE_AVR_TEST_FIRMWARE_DIR) + "/" + name + ".elf",
                   std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
#else
  return {};
#endif
}

#define FIRMWARE_OR_SKIP(var, name)                                                 \
  std::vector<uint8_t> var = Firmware(name);                                        \
  if (var.empty()) {                                                                \
    GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr is missing"; \
  }

// the image's headers, read here on their own from the ELF layout
template <typename T>
T Get(const std::vector<uint8_t>& image, size_t offset) {
  T out;
  std::memcpy(&out, image.data() + offset, sizeof(T));
  return out;
}
template <typename T>
void Put(std::vector<uint8_t>& image, size_t offset, const T& value) {
  std::memcpy(image.data() + offset, &value, sizeof(T));
}
Elf32_Ehdr Header(const std::vector<uint8_t>& image) { return Get<Elf32_Ehdr>(image, 0); }
size_t SectionHeaderAt(const std::vector<uint8_t>& image, const std::string& name) {
  const Elf32_Ehdr h = Header(image);
  const auto names = Get<Elf32_Shdr>(image, h.e_shoff + h.e_shstrndx * sizeof(Elf32_Shdr));
  for (size_t i = 0; i < h.e_shnum; ++i) {
    const size_t at = h.e_shoff + i * sizeof(Elf32_Shdr);
    const auto sh = Get<Elf32_Shdr>(image, at);
    if (name == reinterpret_cast<const char*>(image.data() + names.sh_offset + sh.sh_name)) {
      return at;
    }
  }
  ADD_FAILURE() << "no section " << name;
  return 0;
}

// the message ParseAvrImage refuses the image with, or ""
std::string RefusalOf(const std::vector<uint8_t>& image) {
  try {
    ParseAvrImage(image, "damaged.elf");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AvrImageTest, AnImageNamesItsPartAndClockFromItsMcuSection) {
  FIRMWARE_OR_SKIP(image, "names_its_mcu");
  // tests/avr/names_its_mcu.c: AVR_MCU(8000000, "atmega328p")
  const AvrImage read = ParseAvrImage(image, "names_its_mcu.elf");
  EXPECT_EQ(read.mcu, "atmega328p");
  EXPECT_EQ(read.f_cpu_hz, 8000000u);
  EXPECT_GT(read.text_bytes, 0u);
}

TEST(AvrImageTest, AFileCutShortIsRefusedAtEveryLength) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  // every header, table and section lies before the end; any cut loses one of them
  for (size_t size = 0; size < image.size(); size += 97) {
    const std::vector<uint8_t> cut(image.begin(), image.begin() + static_cast<long>(size));
    EXPECT_EQ(RefusalOf(cut).rfind("damaged.elf: ", 0), 0u) << size;
  }
}

TEST(AvrImageTest, ASixtyFourBitOrForeignElfFileIsRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  std::vector<uint8_t> wide = image;
  wide[EI_CLASS] = ELFCLASS64;
  EXPECT_EQ(RefusalOf(wide), "damaged.elf: an ELF file of another class than AVR's 32-bit one");
  std::vector<uint8_t> foreign = image;
  Put<Elf32_Half>(foreign, offsetof(Elf32_Ehdr, e_machine), EM_386);
  EXPECT_EQ(RefusalOf(foreign), "damaged.elf: an ELF file for machine 3, not for the AVR (83)");
}

TEST(AvrImageTest, SectionHeadersBeyondTheEndOfTheFileAreRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  Put<Elf32_Off>(image, offsetof(Elf32_Ehdr, e_shoff), static_cast<Elf32_Off>(image.size() - 8));
  EXPECT_EQ(RefusalOf(image), "damaged.elf: its section headers lie beyond the end of the file");
}

TEST(AvrImageTest, ASectionWhoseBytesLieBeyondTheFileIsRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  const size_t text = SectionHeaderAt(image, ".text");
  Put<Elf32_Word>(image, text + offsetof(Elf32_Shdr, sh_size), 0x7fffffff);
  const size_t index = (text - Header(image).e_shoff) / sizeof(Elf32_Shdr);
  EXPECT_EQ(RefusalOf(image),
            "damaged.elf: section " + std::to_string(index) + " lies beyond the end of the file");
}

TEST(AvrImageTest, AProgramHeaderBeyondTheFileIsRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  Put<Elf32_Off>(image, Header(image).e_phoff + offsetof(Elf32_Phdr, p_offset),
                 static_cast<Elf32_Off>(image.size()));
  EXPECT_EQ(RefusalOf(image), "damaged.elf: program header 0 lies beyond the end of the file");
}

TEST(AvrImageTest, ASymbolTableOfZeroSizedEntriesIsRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  // simavr divides the table's size by this
  const size_t symtab = SectionHeaderAt(image, ".symtab");
  Put<Elf32_Word>(image, symtab + offsetof(Elf32_Shdr, sh_entsize), 0);
  EXPECT_NE(RefusalOf(image).find("is not a whole number of symbols"), std::string::npos);
}

TEST(AvrImageTest, ASymbolNamedOutsideItsStringTableIsRefused) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  const auto symtab = Get<Elf32_Shdr>(image, SectionHeaderAt(image, ".symtab"));
  Put<Elf32_Word>(image, symtab.sh_offset + 3 * sizeof(Elf32_Sym) + offsetof(Elf32_Sym, st_name),
                  0x00ffffff);
  EXPECT_EQ(RefusalOf(image), "damaged.elf: the name of symbol 3 lies outside its string table");
}

TEST(AvrImageTest, AnMcuTagLongerThanItsSectionOrANameWithoutItsEndIsRefused) {
  FIRMWARE_OR_SKIP(image, "names_its_mcu");
  const auto mmcu = Get<Elf32_Shdr>(image, SectionHeaderAt(image, ".mmcu"));
  // an empty tag [0][0], the clock [2][4][4 bytes], the name [1][64][text]
  ASSERT_EQ(image[mmcu.sh_offset + 2], 2);
  std::vector<uint8_t> long_tag = image;
  long_tag[mmcu.sh_offset + 3] = 0xff;
  EXPECT_EQ(RefusalOf(long_tag),
            "damaged.elf: a tag of the .mmcu section claims 255 bytes, more than the section has "
            "left");
  ASSERT_EQ(image[mmcu.sh_offset + 8], 1);
  std::vector<uint8_t> endless = image;
  std::memset(endless.data() + mmcu.sh_offset + 10, 'a', 64);
  EXPECT_EQ(RefusalOf(endless),
            "damaged.elf: the .mmcu section's part name does not end inside its tag");
}

TEST(AvrImageTest, AnMcuSectionNamingAPartTheBoardDoesNotKnowIsRefused) {
  FIRMWARE_OR_SKIP(image, "names_its_mcu");
  const auto mmcu = Get<Elf32_Shdr>(image, SectionHeaderAt(image, ".mmcu"));
  // "atmega328p" becomes "atmega8", a part simavr knows but whose UART sits elsewhere
  std::memcpy(image.data() + mmcu.sh_offset + 10, "atmega8\0", 8);
  EXPECT_EQ(RefusalOf(image),
            "damaged.elf: the .mmcu section names the part 'atmega8'; the emulated board is an "
            "atmega2560 or an atmega328p");
}

TEST(AvrImageTest, AnMcuClockOutsideTheLinksRangeIsRefused) {
  FIRMWARE_OR_SKIP(image, "names_its_mcu");
  const auto mmcu = Get<Elf32_Shdr>(image, SectionHeaderAt(image, ".mmcu"));
  ASSERT_EQ(image[mmcu.sh_offset + 2], 2);
  Put<uint32_t>(image, mmcu.sh_offset + 4, 1000);
  EXPECT_EQ(RefusalOf(image),
            "damaged.elf: the .mmcu section's clock of 1000 Hz is outside 1 to 32 MHz");
}

// the ATmega2560 as its datasheet gives it
const AvrMemory kMega{"atmega2560", 262144, 0x200, 0x21ff, 4096, 3};

TEST(AvrImageTest, DataOutsideThePartsRamIsRefused) {
  AvrImage image;
  image.text_bytes = 100;
  image.data_bytes = 16;
  image.data_address = 0x800200;
  EXPECT_NO_THROW(CheckAvrImageFits(image, kMega, "ok.elf"));
  image.data_address = 0x8021f8;  // 8 bytes short of RAMEND + 1
  try {
    CheckAvrImageFits(image, kMega, "high.elf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "high.elf: its .data (16 bytes at 0x8021f8) lies outside the RAM of the "
                 "atmega2560");
  }
}

TEST(AvrImageTest, EepromDataLargerThanThePartsEepromIsRefused) {
  AvrImage image;
  image.text_bytes = 100;
  image.eeprom_bytes = 4097;
  try {
    CheckAvrImageFits(image, kMega, "ee.elf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "ee.elf: its 4097 bytes of EEPROM data do not fit the 4096 bytes of EEPROM of "
                 "the atmega2560");
  }
}

TEST(AvrImageTest, MallocsBreakOutsideRamIsRefused) {
  // the board reads __brkval's two bytes from RAM at every new stack depth
  AvrImage image;
  image.text_bytes = 100;
  image.symbols.push_back({"__brkval", 0x8021ff, 2, false});
  EXPECT_THROW(CheckAvrImageFits(image, kMega, "brk.elf"), InputError);
  image.symbols.back().value = 0x8021fe;
  EXPECT_NO_THROW(CheckAvrImageFits(image, kMega, "brk.elf"));
}

TEST(AvrImageTest, ASegmentInNoMemoryIsRefused) {
  AvrImage image;
  image.text_bytes = 100;
  image.segments.push_back({0x900000, 0x900000, 0, 4});
  try {
    CheckAvrImageFits(image, kMega, "far.elf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "far.elf: a segment at 0x900000 lies in none of the memories of the "
                 "atmega2560");
  }
}

// each of these crashes simavr's own reader (a division by zero, a name read through a null
// pointer): the board refuses them before it is asked
TEST(AvrImageTest, TheBoardRefusesImagesThatCrashedSimavrsReader) {
  FIRMWARE_OR_SKIP(image, "millis_clock");
  const std::string dir = testing::FreshDirectory("avr_image");
  const size_t symtab = SectionHeaderAt(image, ".symtab");
  std::vector<uint8_t> no_entries = image;
  Put<Elf32_Word>(no_entries, symtab + offsetof(Elf32_Shdr, sh_entsize), 0);
  // simavr names only global symbols, functions and objects
  const auto table = Get<Elf32_Shdr>(image, symtab);
  size_t global = table.sh_offset;
  while (ELF32_ST_BIND(Get<Elf32_Sym>(image, global).st_info) != STB_GLOBAL) {
    global += sizeof(Elf32_Sym);
    ASSERT_LT(global, table.sh_offset + table.sh_size) << "no global symbol";
  }
  std::vector<uint8_t> far_name = image;
  Put<Elf32_Word>(far_name, global + offsetof(Elf32_Sym, st_name), 0x00ffffff);
  std::vector<uint8_t> bss_name = image;
  // .bss named from outside the section names' table
  Put<Elf32_Word>(bss_name, SectionHeaderAt(image, ".bss") + offsetof(Elf32_Shdr, sh_name),
                  0x00ffffff);
  int n = 0;
  for (const auto* damaged : {&no_entries, &far_name, &bss_name}) {
    const std::string path = dir + "/damaged" + std::to_string(n++) + ".elf";
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(damaged->data()),
               static_cast<std::streamsize>(damaged->size()));
    EXPECT_THROW(AvrBoard(path, {}), InputError) << path;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace unimouse::link
