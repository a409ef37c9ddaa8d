// SPDX-License-Identifier: GPL-3.0-or-later
#include "avr_image.h"

#include <elf.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <map>
#include <optional>

#include "unimouse/errors.h"

extern "C" {
#include "avr/avr_mcu_section.h"
}

namespace unimouse::link {
namespace {

// avr-ld's view of the AVR's separate memories as one address space
constexpr uint32_t kRamSpace = 0x800000, kEepromSpace = 0x810000, kFuseSpace = 0x820000,
                   kLockSpace = 0x830000, kSignatureSpace = 0x840000, kSpacesEnd = 0x850000;
// simavr's I/O registers: data addresses 0x20 up to 0x20 + MAX_IOs (sim_avr.h)
constexpr uint32_t kFirstIo = 0x20, kIoCount = 280;
// what simavr's reader keeps of the .mmcu section (sim_elf.h)
constexpr size_t kMcuName_bytes = 64, kTraceName_bytes = 128, kMaxTraces = 32;
// the link's own bounds for the clock (link.h), which an image's clock meets too
constexpr uint32_t kMinClock_hz = 1000000, kMaxClock_hz = 32000000;

std::string Hex(uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof(text), "0x%llx", static_cast<unsigned long long>(value));
  return text;
}

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  [[noreturn]] void Fail(const std::string& why) const { throw InputError(path_ + ": " + why); }

  // whether [offset, offset + size) lies inside the file, without overflow
  bool Inside(uint64_t offset, uint64_t size) const {
    return offset <= bytes_.size() && size <= bytes_.size() - offset;
  }

  template <typename T>
  T At(uint64_t offset) const {
    T out;
    std::memcpy(&out, bytes_.data() + offset, sizeof(T));
    return out;
  }

  std::span<const uint8_t> Bytes(uint64_t offset, uint64_t size) const {
    return bytes_.subspan(offset, size);
  }

  size_t size() const { return bytes_.size(); }

 private:
  std::span<const uint8_t> bytes_;
  const std::string& path_;
};

// a string table's string at `offset`, which must end inside the table
std::optional<std::string> StringAt(std::span<const uint8_t> table, uint32_t offset) {
  if (offset >= table.size()) return std::nullopt;
  const auto begin = table.begin() + offset;
  const auto end = std::find(begin, table.end(), uint8_t{0});
  if (end == table.end()) return std::nullopt;
  return std::string(begin, end);
}

uint32_t Le32(std::span<const uint8_t> b) {
  return uint32_t{b[0]} | uint32_t{b[1]} << 8 | uint32_t{b[2]} << 16 | uint32_t{b[3]} << 24;
}

// simavr's .mmcu section: tags of [tag][length][length bytes]; its reader trusts every length
void ReadMcuSection(const Reader& r, std::span<const uint8_t> mmcu, AvrImage& image) {
  size_t traces = 0;
  while (!mmcu.empty()) {
    if (mmcu.size() < 2) r.Fail("the .mmcu section ends inside a tag");
    const uint8_t tag = mmcu[0];
    const size_t length = mmcu[1];
    if (2 + length > mmcu.size()) {
      r.Fail("a tag of the .mmcu section claims " + std::to_string(length) +
             " bytes, more than the section has left");
    }
    const std::span<const uint8_t> value = mmcu.subspan(2, length);
    const auto need = [&](size_t bytes, const char* what) {
      if (value.size() < bytes) {
        r.Fail(std::string("the .mmcu section's ") + what + " is " + std::to_string(value.size()) +
               " bytes, not " + std::to_string(bytes));
      }
    };
    // a text must end inside its tag and fit simavr's field for it
    const auto text = [&](size_t from, size_t field_bytes, const char* what) {
      const auto end = std::find(value.begin() + static_cast<long>(std::min(from, value.size())),
                                 value.end(), uint8_t{0});
      if (end == value.end()) {
        r.Fail(std::string("the .mmcu section's ") + what + " does not end inside its tag");
      }
      const auto chars = static_cast<size_t>(end - value.begin()) - from;
      if (chars >= field_bytes) {
        r.Fail(std::string("the .mmcu section's ") + what + " is longer than " +
               std::to_string(field_bytes - 1) + " characters");
      }
      return std::string(value.begin() + static_cast<long>(from), end);
    };
    switch (tag) {
      case AVR_MMCU_TAG_NAME:
        image.mcu = text(0, kMcuName_bytes, "part name");
        // the board's UART and the link's `mcu` parameter know these two parts only
        if (image.mcu != "atmega2560" && image.mcu != "atmega328p") {
          r.Fail("the .mmcu section names the part '" + image.mcu +
                 "'; the emulated board is an atmega2560 or an atmega328p");
        }
        break;
      case AVR_MMCU_TAG_FREQUENCY:
        need(4, "clock");
        image.f_cpu_hz = Le32(value);
        if (image.f_cpu_hz != 0 &&
            (image.f_cpu_hz < kMinClock_hz || image.f_cpu_hz > kMaxClock_hz)) {
          r.Fail("the .mmcu section's clock of " + std::to_string(image.f_cpu_hz) +
                 " Hz is outside 1 to 32 MHz");
        }
        break;
      case AVR_MMCU_TAG_VCC:
      case AVR_MMCU_TAG_AVCC:
      case AVR_MMCU_TAG_AREF:
        need(4, "voltage");
        break;
      case AVR_MMCU_TAG_VCD_PERIOD:
        need(4, "trace period");
        break;
      case AVR_MMCU_TAG_PORT_EXTERNAL_PULL:
        need(3, "pull-up");
        break;
      case AVR_MMCU_TAG_SIMAVR_COMMAND:
      case AVR_MMCU_TAG_SIMAVR_CONSOLE: {
        need(2, "register");
        const auto address = static_cast<uint16_t>(value[0] | value[1] << 8);
        if (address != 0 && (address < kFirstIo || address >= kFirstIo + kIoCount)) {
          r.Fail("the .mmcu section names " + Hex(address) +
                 " as simavr's command or console register, which is no I/O register");
        }
        (tag == AVR_MMCU_TAG_SIMAVR_COMMAND ? image.command_register : image.console_register) =
            address;
        break;
      }
      case AVR_MMCU_TAG_VCD_FILENAME:
        text(0, kTraceName_bytes, "trace file name");
        break;
      case AVR_MMCU_TAG_VCD_TRACE:
      case AVR_MMCU_TAG_VCD_PORTPIN:
      case AVR_MMCU_TAG_VCD_IRQ:
        need(3, "trace");
        text(3, kMcuName_bytes, "trace name");
        if (++traces > kMaxTraces) {
          r.Fail("the .mmcu section asks for more than " + std::to_string(kMaxTraces) + " traces");
        }
        break;
      default:
        // simavr skips the others by their length
        break;
    }
    mmcu = mmcu.subspan(2 + length);
  }
}

}  // namespace

AvrImage ParseAvrImage(std::span<const uint8_t> bytes, const std::string& path) {
  const Reader r(bytes, path);
  AvrImage image;
  if (!r.Inside(0, EI_NIDENT) || std::memcmp(bytes.data(), ELFMAG, SELFMAG) != 0) {
    r.Fail("not an ELF file, so no AVR image");
  }
  if (bytes[EI_CLASS] != ELFCLASS32) r.Fail("an ELF file of another class than AVR's 32-bit one");
  if (bytes[EI_DATA] != ELFDATA2LSB) r.Fail("an ELF file that is not little-endian, as AVR's are");
  if (bytes[EI_VERSION] != EV_CURRENT) r.Fail("an ELF file of an unknown version");
  if (!r.Inside(0, sizeof(Elf32_Ehdr))) r.Fail("an ELF file cut short inside its header");
  // simavr reads the header as it lies in the file
  if constexpr (std::endian::native != std::endian::little) {
    r.Fail("the emulated board needs a little-endian host");
  }
  const auto header = r.At<Elf32_Ehdr>(0);
  if (header.e_machine != EM_AVR) {
    r.Fail("an ELF file for machine " + std::to_string(header.e_machine) + ", not for the AVR (" +
           std::to_string(EM_AVR) + ")");
  }
  if (header.e_ehsize != sizeof(Elf32_Ehdr)) r.Fail("an ELF header of an unknown size");

  // program headers: each inside the file
  if (header.e_phnum > 0) {
    if (header.e_phentsize != sizeof(Elf32_Phdr)) r.Fail("program headers of an unknown size");
    if (header.e_phnum > kMaxAvrImageHeaders) r.Fail("more program headers than an image has");
    if (!r.Inside(header.e_phoff, uint64_t{header.e_phnum} * sizeof(Elf32_Phdr))) {
      r.Fail("its program headers lie beyond the end of the file");
    }
  }
  for (uint32_t i = 0; i < header.e_phnum; ++i) {
    const auto ph = r.At<Elf32_Phdr>(header.e_phoff + uint64_t{i} * sizeof(Elf32_Phdr));
    if (!r.Inside(ph.p_offset, ph.p_filesz)) {
      r.Fail("program header " + std::to_string(i) + " lies beyond the end of the file");
    }
    if (ph.p_type != PT_LOAD) continue;
    if (ph.p_filesz > ph.p_memsz) {
      r.Fail("program header " + std::to_string(i) + " holds more bytes than it loads");
    }
    image.segments.push_back({ph.p_vaddr, ph.p_paddr, ph.p_filesz, ph.p_memsz});
  }

  // section headers: each inside the file, named from a string table
  if (header.e_shoff == 0 || header.e_shnum == 0) r.Fail("an ELF file without sections");
  if (header.e_shentsize != sizeof(Elf32_Shdr)) r.Fail("section headers of an unknown size");
  if (header.e_shnum > kMaxAvrImageHeaders) r.Fail("more sections than an image has");
  if (!r.Inside(header.e_shoff, uint64_t{header.e_shnum} * sizeof(Elf32_Shdr))) {
    r.Fail("its section headers lie beyond the end of the file");
  }
  std::vector<Elf32_Shdr> sections(header.e_shnum);
  for (uint32_t i = 0; i < header.e_shnum; ++i) {
    sections[i] = r.At<Elf32_Shdr>(header.e_shoff + uint64_t{i} * sizeof(Elf32_Shdr));
    const Elf32_Shdr& sh = sections[i];
    if (i > 0 && sh.sh_type != SHT_NOBITS && !r.Inside(sh.sh_offset, sh.sh_size)) {
      r.Fail("section " + std::to_string(i) + " lies beyond the end of the file");
    }
  }
  const auto string_table = [&](uint32_t index, const std::string& of) {
    if (index == SHN_UNDEF || index >= sections.size() || sections[index].sh_type != SHT_STRTAB ||
        (sections[index].sh_flags & SHF_COMPRESSED) != 0) {
      r.Fail("the string table of " + of + " is no string table");
    }
    return r.Bytes(sections[index].sh_offset, sections[index].sh_size);
  };
  const std::span<const uint8_t> names = string_table(header.e_shstrndx, "the section names");

  std::map<std::string, uint32_t> loaded;  // the sections simavr reads by name, to their index
  uint32_t symbol_count = 0;
  for (uint32_t i = 1; i < sections.size(); ++i) {
    const Elf32_Shdr& sh = sections[i];
    const std::optional<std::string> name = StringAt(names, sh.sh_name);
    if (!name)
      r.Fail("the name of section " + std::to_string(i) + " lies outside its string table");
    if (*name == ".text" || *name == ".data" || *name == ".eeprom" || *name == ".fuse" ||
        *name == ".lock" || *name == ".mmcu" || *name == ".bss") {
      if (!loaded.emplace(*name, i).second) r.Fail("two sections named " + *name);
      const uint32_t type = *name == ".bss" ? SHT_NOBITS : SHT_PROGBITS;
      if (sh.sh_type != type || (sh.sh_flags & SHF_COMPRESSED) != 0) {
        r.Fail("its " + *name + " section is not of the kind a compiler makes (" +
               (type == SHT_NOBITS ? "NOBITS" : "PROGBITS") + ")");
      }
    }
    if (sh.sh_type != SHT_SYMTAB) continue;
    if (sh.sh_entsize != sizeof(Elf32_Sym) || sh.sh_size % sizeof(Elf32_Sym) != 0 ||
        (sh.sh_flags & SHF_COMPRESSED) != 0) {
      r.Fail("its symbol table (section " + std::to_string(i) +
             ") is not a whole number of symbols");
    }
    const std::span<const uint8_t> strings =
        string_table(sh.sh_link, "the symbols of section " + std::to_string(i));
    const uint32_t count = sh.sh_size / sizeof(Elf32_Sym);
    symbol_count += count;
    if (symbol_count > kMaxAvrImageSymbols) {
      r.Fail("more than " + std::to_string(kMaxAvrImageSymbols) + " symbols");
    }
    for (uint32_t k = 0; k < count; ++k) {
      const auto sym = r.At<Elf32_Sym>(sh.sh_offset + uint64_t{k} * sizeof(Elf32_Sym));
      const std::optional<std::string> symbol = StringAt(strings, sym.st_name);
      if (!symbol) {
        r.Fail("the name of symbol " + std::to_string(k) + " lies outside its string table");
      }
      if (sym.st_shndx >= sections.size() && sym.st_shndx < SHN_LORESERVE) {
        r.Fail("symbol '" + *symbol + "' belongs to a section that does not exist");
      }
      if (symbol->empty()) continue;
      if (*symbol == "__vectors") image.flash_base = sym.st_value;
      image.symbols.push_back(
          {*symbol, sym.st_value, sym.st_size, ELF32_ST_TYPE(sym.st_info) == STT_FUNC});
    }
  }

  const auto size_of = [&](const char* name) {
    const auto it = loaded.find(name);
    return it == loaded.end() ? 0u : sections[it->second].sh_size;
  };
  image.text_bytes = size_of(".text");
  image.data_bytes = size_of(".data");
  image.bss_bytes = size_of(".bss");
  image.eeprom_bytes = size_of(".eeprom");
  image.fuse_bytes = size_of(".fuse");
  image.lock_bytes = size_of(".lock");
  if (loaded.count(".data")) image.data_address = sections[loaded[".data"]].sh_addr;
  if (loaded.count(".bss")) image.bss_address = sections[loaded[".bss"]].sh_addr;
  if (image.text_bytes == 0) r.Fail("an ELF file without a program (no .text section)");
  // simavr 1.6 copies the lock bits from the fuses' section
  if (loaded.count(".lock") && image.fuse_bytes == 0) {
    r.Fail(
        "lock bits (.lock) without fuses (.fuse), which the emulated board cannot load: give the "
        "part's fuses too, or leave the lock bits out");
  }
  if (loaded.count(".mmcu")) {
    const Elf32_Shdr& sh = sections[loaded[".mmcu"]];
    ReadMcuSection(r, r.Bytes(sh.sh_offset, sh.sh_size), image);
  }
  return image;
}

AvrImage ReadAvrImage(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": no such firmware image");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    throw InputError(path + ": no such firmware image");
  }
  if (static_cast<uint64_t>(st.st_size) > kMaxAvrImage_bytes) {
    throw InputError(path + ": " + std::to_string(st.st_size) +
                     " bytes, more than an AVR image may be (16 MiB)");
  }
  std::vector<uint8_t> bytes(static_cast<size_t>(st.st_size));
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n <= 0) throw InputError(path + ": cannot be read");
    got += static_cast<size_t>(n);
  }
  return ParseAvrImage(bytes, path);
}

void CheckAvrImageFits(const AvrImage& image, const AvrMemory& memory, const std::string& path) {
  const auto fail = [&](const std::string& why) {
    throw InputError(path + ": " + why + " of the " + memory.mcu);
  };
  const uint64_t ram_bytes = uint64_t{memory.ram_end} + 1;
  // simavr puts .text and then .data at __vectors
  const uint64_t flash_image = uint64_t{image.text_bytes} + image.data_bytes;
  if (image.flash_base + flash_image > memory.flash_bytes) {
    fail("an image of " + std::to_string(flash_image) + " bytes from " + Hex(image.flash_base) +
         " does not fit the " + std::to_string(memory.flash_bytes) + " bytes of flash");
  }
  const auto in_ram = [&](uint32_t address, uint32_t size, const char* what) {
    if (size == 0) return;
    if (address < kRamSpace + memory.ram_start ||
        uint64_t{address} + size > kRamSpace + ram_bytes) {
      fail(std::string("its ") + what + " (" + std::to_string(size) + " bytes at " + Hex(address) +
           ") lies outside the RAM");
    }
  };
  in_ram(image.data_address, image.data_bytes, ".data");
  in_ram(image.bss_address, image.bss_bytes, ".bss");
  if (image.eeprom_bytes > memory.eeprom_bytes) {
    fail("its " + std::to_string(image.eeprom_bytes) + " bytes of EEPROM data do not fit the " +
         std::to_string(memory.eeprom_bytes) + " bytes of EEPROM");
  }
  if (image.fuse_bytes > memory.fuse_bytes) fail("more fuse bytes than there are");
  if (image.lock_bytes > 1) fail("more than the one byte of lock bits");

  // every loadable segment in the memory its address names
  for (const AvrImage::Segment& s : image.segments) {
    const uint64_t end = uint64_t{s.address} + s.memory_bytes;
    uint64_t base = 0, room = 0;
    const char* where = "";
    if (s.address < kRamSpace) {
      base = 0, room = memory.flash_bytes, where = "flash";
    } else if (s.address < kEepromSpace) {
      base = kRamSpace, room = ram_bytes, where = "RAM";
    } else if (s.address < kFuseSpace) {
      base = kEepromSpace, room = memory.eeprom_bytes, where = "EEPROM";
    } else if (s.address < kLockSpace) {
      base = kFuseSpace, room = memory.fuse_bytes, where = "fuses";
    } else if (s.address < kSignatureSpace) {
      base = kLockSpace, room = 1, where = "lock bits";
    } else if (s.address < kSpacesEnd) {
      base = kSignatureSpace, room = 3, where = "signature";
    } else {
      fail("a segment at " + Hex(s.address) + " lies in none of the memories");
    }
    if (end > base + room) {
      fail("a segment of " + std::to_string(s.memory_bytes) + " bytes at " + Hex(s.address) +
           " runs past the end of the " + where);
    }
    // initialised data is kept in flash, at its load address
    if (where == std::string("RAM") && s.file_bytes > 0 &&
        uint64_t{s.load_address} + s.file_bytes > memory.flash_bytes) {
      fail("the initial values of a segment at " + Hex(s.address) + " lie beyond the flash");
    }
  }

  // the symbols that say where the data, the heap and malloc's break are
  for (const AvrImage::Symbol& symbol : image.symbols) {
    uint32_t bytes = 0;
    if (symbol.name == "__brkval") {
      bytes = 2;
    } else if (symbol.name == "__data_start" || symbol.name == "__heap_start" ||
               symbol.name == "_end") {
      bytes = 0;
    } else {
      continue;
    }
    if (symbol.value < kRamSpace || symbol.value >= kEepromSpace) continue;
    const uint64_t address = symbol.value - kRamSpace;
    if (address < memory.ram_start || address + bytes > ram_bytes) {
      fail("its symbol " + symbol.name + " (" + Hex(symbol.value) + ") lies outside the RAM");
    }
  }
}

}  // namespace unimouse::link
