// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as an AVR image for the emulated board: refused with an InputError, or loaded by
// simavr onto a fresh MCU. An image the check lets through must never crash simavr's reader.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "avr_board.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // the board reads a path, as simavr does: a file in memory, named through /proc
  static const int fd = ::memfd_create("fuzz_avr_image", 0);
  static const std::string path = "/proc/self/fd/" + std::to_string(fd);
  if (fd < 0 || ::ftruncate(fd, 0) != 0 ||
      ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) {
    return 0;
  }
  try {
    unimouse::link::AvrBoard board(path, {});
    // a few steps of its code: the load is what is checked here, the run is simavr's own
    board.RunUntil(1000);
  } catch (const unimouse::InputError&) {
    // bad input is the expected answer to most bytes
  }
  return 0;
}
