// SPDX-License-Identifier: MIT
// Arduino's EEPROM library for the PC core: a Mega 2560's 4 KiB, erased (0xFF) at the start of
// every run, so that a run depends on its inputs alone (a board keeps its EEPROM across resets).
#ifndef UNIMOUSE_PC_EEPROM_H_
#define UNIMOUSE_PC_EEPROM_H_

#include <stdint.h>
#include <string.h>

class EEPROMClass {
 public:
  EEPROMClass() { memset(bytes_, 0xFF, sizeof(bytes_)); }
  uint8_t read(int address) const { return Inside(address) ? bytes_[address] : 0; }
  void write(int address, uint8_t value) {
    if (Inside(address)) bytes_[address] = value;
  }
  void update(int address, uint8_t value) { write(address, value); }
  uint8_t& operator[](int address) { return bytes_[Inside(address) ? address : 0]; }
  uint16_t length() const { return sizeof(bytes_); }
  /// Reads (writes) a value's bytes from (to) `address` on, as the board's library does.
  template <typename T>
  T& get(int address, T& value) const {
    if (Inside(address) && address + sizeof(T) <= sizeof(bytes_)) {
      memcpy(&value, bytes_ + address, sizeof(T));
    }
    return value;
  }
  template <typename T>
  const T& put(int address, const T& value) {
    if (Inside(address) && address + sizeof(T) <= sizeof(bytes_)) {
      memcpy(bytes_ + address, &value, sizeof(T));
    }
    return value;
  }

 private:
  static bool Inside(int address) { return address >= 0 && address < 4096; }
  uint8_t bytes_[4096];
};

inline EEPROMClass EEPROM;

#endif  // UNIMOUSE_PC_EEPROM_H_
