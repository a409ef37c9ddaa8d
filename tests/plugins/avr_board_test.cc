// SPDX-License-Identifier: GPL-3.0-or-later
// The emulated board on its own, with the small firmwares of tests/avr: its clock is simulated
// time, its receiver overflows as a real one does, a stack that runs into the data and the
// ways a firmware can stop for good (a write beyond its SRAM among them) end its run with a
// reason, a reset (watchdog, reset pin, brown-out) boots the image again, and two runs are the
// same.
#include "avr_board.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

std::string Firmware(const std::string& name) {
#ifdef UNIMOUSE_AVR_TEST_FIRMWARE_DIR
  const std::string path = std::string(UNIMOUSE_AVR_TEST_FIRMWARE_DIR) + "/" + name + ".elf";
  if (std::filesystem::exists(path)) return path;
#endif
  return "";
}

#define FIRMWARE_OR_SKIP(var, name)                                                 \
  const std::string var = Firmware(name);                                           \
  if (var.empty()) {                                                                \
    GTEST_SKIP() << "no AVR test firmware: gcc-avr or arduino-core-avr is missing"; \
  }

constexpr uint64_t kCyclesPerMs = 16000;

TEST(AvrBoardTest, MillisIsSimulatedTime) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  AvrBoard board(elf, {});
  std::vector<uint8_t> in;
  int answers = 0;
  for (uint64_t ms = 1; ms <= 3000; ++ms) {
    // a question every 250 ms; the answer comes within the step
    if (ms % 250 == 0) board.Write(std::vector<uint8_t>{0x55});
    ASSERT_EQ(board.RunUntil(ms * kCyclesPerMs), "");
    board.Read(in);
    if (in.size() >= 4) {
      const uint32_t millis = in[0] | in[1] << 8 | in[2] << 16 | static_cast<uint32_t>(in[3]) << 24;
      // asked at ms - 1 (the step's start): millis() counts timer0's 1.024 ms overflows and
      // catches up on the 0.024 ms in whole milliseconds, so it trails by less than 2.05 ms
      const double asked_ms = static_cast<double>(ms - 1);
      EXPECT_LE(millis, asked_ms) << "at " << ms;
      EXPECT_GT(millis, asked_ms - 2.05) << "at " << ms;
      in.erase(in.begin(), in.begin() + 4);
      ++answers;
    }
  }
  EXPECT_EQ(answers, 12);
  const AvrBoardStats s = board.stats();
  EXPECT_EQ(s.mcu, "atmega2560");
  EXPECT_EQ(s.baud, 1000000u);
  EXPECT_GE(s.cycles, 3000 * kCyclesPerMs);
  EXPECT_LE(s.cycles, 3000 * kCyclesPerMs + 4);  // one instruction past the boundary at most
  EXPECT_EQ(s.rx_overruns, 0u);
  EXPECT_GT(s.ram_high_water_bytes, s.static_bytes);
  EXPECT_LT(s.ram_high_water_bytes, 1024u);
  EXPECT_EQ(s.sram_bytes, 8192u);
}

TEST(AvrBoardTest, BytesBeforeTheReceiverIsOnAreLost) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  AvrBoard board(elf, {});
  board.Write(std::vector<uint8_t>{0x55, 0x55});  // at reset: Serial.begin() has not run
  ASSERT_EQ(board.RunUntil(10 * kCyclesPerMs), "");
  std::vector<uint8_t> in;
  board.Read(in);
  EXPECT_TRUE(in.empty());
  EXPECT_EQ(board.stats().before_receiver_on, 2u);
  EXPECT_TRUE(board.receiver_on());
}

TEST(AvrBoardTest, AReceiverNobodyReadsOverflowsAndCountsTheOverruns) {
  FIRMWARE_OR_SKIP(elf, "rx_overflow");
  AvrBoard board(elf, {});
  ASSERT_EQ(board.RunUntil(kCyclesPerMs), "");
  ASSERT_TRUE(board.receiver_on());
  board.Write(std::vector<uint8_t>(200, 0xA5));
  ASSERT_EQ(board.RunUntil(20 * kCyclesPerMs), "");
  const AvrBoardStats s = board.stats();
  // simavr's receiver holds 63 bytes; the line does not wait for room
  EXPECT_EQ(s.bytes_to_mcu, 63u);
  EXPECT_EQ(s.rx_overruns, 137u);
  EXPECT_EQ(s.dropped_to_mcu, 137u);
  // the user is told once, and why
  EXPECT_EQ(board.TakeNotices(),
            std::vector<std::string>{"bytes for the board are being lost: its UART received a byte "
                                     "before the firmware had read the one before (interrupts "
                                     "off for too long?)"});
  // more than the line's queue holds (1024 bytes) in one write, twice: said once
  board.Write(std::vector<uint8_t>(2000, 0xA5));
  board.Write(std::vector<uint8_t>(2000, 0xA5));
  ASSERT_EQ(board.RunUntil(21 * kCyclesPerMs), "");
  EXPECT_EQ(board.stats().dropped_to_mcu, 137u + 4000u);  // each write lost whole
  EXPECT_EQ(board.TakeNotices(),
            std::vector<std::string>{"bytes for the board are being lost: its serial line at "
                                     "1000000 baud carries fewer than the simulator sends"});
}

TEST(AvrBoardTest, AStackIntoTheDataStopsTheBoardWithItsHighWaterMark) {
  FIRMWARE_OR_SKIP(elf, "stack_overflow");
  AvrBoard board(elf, {});
  const std::string why = board.RunUntil(100 * kCyclesPerMs);
  EXPECT_NE(why.find("stack"), std::string::npos) << why;
  EXPECT_NE(why.find("recurse"), std::string::npos) << why;
  EXPECT_NE(why.find("pc 0x"), std::string::npos) << why;
  const AvrBoardStats s = board.stats();
  EXPECT_GE(s.static_bytes, 4096u);
  EXPECT_GE(s.ram_high_water_bytes, s.sram_bytes);
  EXPECT_LT(s.cycles, 100 * kCyclesPerMs);
  // it stays stopped
  EXPECT_EQ(board.RunUntil(200 * kCyclesPerMs), why);
}

// simavr 1.6 reports such a write as a crash and then makes it: the board gives it room, so
// that the write lands in the board's own memory rather than over the simulator's
TEST(AvrBoardTest, AWriteBeyondTheSramStopsTheBoardAndHarmsNothingElse) {
  FIRMWARE_OR_SKIP(elf, "ram_overrun");
  FIRMWARE_OR_SKIP(next, "millis_clock");
  for (int run = 0; run < 3; ++run) {
    AvrBoard board(elf, {});
    const std::string why = board.RunUntil(10 * kCyclesPerMs);
    EXPECT_NE(why.find("it crashed"), std::string::npos) << why;
    EXPECT_NE(why.find("(main)"), std::string::npos) << why;
  }
  AvrBoard board(next, {});
  EXPECT_EQ(board.RunUntil(10 * kCyclesPerMs), "");
}

TEST(AvrBoardTest, SleepingWithInterruptsOffStopsTheBoard) {
  FIRMWARE_OR_SKIP(elf, "sleep_cli");
  AvrBoard board(elf, {.mcu = "atmega328p"});
  const std::string why = board.RunUntil(10 * kCyclesPerMs);
  EXPECT_NE(why.find("sleep with interrupts off"), std::string::npos) << why;
  EXPECT_NE(why.find("main"), std::string::npos) << why;
}

TEST(AvrBoardTest, AWatchdogResetStopsTheBoardWhenResetsAreFailures) {
  FIRMWARE_OR_SKIP(elf, "watchdog");
  AvrBoard board(elf, {.mcu = "atmega328p", .resets_restart = false});
  const std::string why = board.RunUntil(100 * kCyclesPerMs);
  EXPECT_NE(why.find("watchdog"), std::string::npos) << why;
  // 15 ms nominal; simavr times it from its own 128 kHz oscillator
  EXPECT_GT(board.stats().emulated_s(), 0.012);
  EXPECT_LT(board.stats().emulated_s(), 0.03);
}

// MCUSR's flags
constexpr uint8_t kExtrf = 0x02, kBorf = 0x04, kWdrf = 0x08;

TEST(AvrBoardTest, AWatchdogResetBootsTheFirmwareAgainAsOnTheBoard) {
  FIRMWARE_OR_SKIP(elf, "watchdog");
  AvrBoard board(elf, {.mcu = "atmega328p"});
  // the image arms the watchdog and hangs: each 15 ms (simavr's 128 kHz oscillator: a little
  // more) the MCU resets and the image starts again
  ASSERT_EQ(board.RunUntil(100 * kCyclesPerMs), "");
  EXPECT_NEAR(board.stats().emulated_s(), 0.1, 1e-6);  // the board's time runs on
  const std::vector<std::string> resets = board.TakeResets();
  EXPECT_GE(resets.size(), 4u);
  EXPECT_LE(resets.size(), 7u);
  for (const std::string& cause : resets) EXPECT_EQ(cause, "the watchdog");
  EXPECT_TRUE(board.TakeResets().empty());  // taken once
}

TEST(AvrBoardTest, AResetPinOrBrownOutRestartsTheMcuAndMcusrSaysWhich) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  AvrBoard board(elf, {});
  ASSERT_EQ(board.RunUntil(20 * kCyclesPerMs), "");
  EXPECT_TRUE(board.receiver_on());
  board.Reset(AvrBoard::ResetCause::kBrownOut);
  EXPECT_EQ(board.pc(), 0u);
  EXPECT_FALSE(board.receiver_on());  // Serial.begin() has not run again yet
  EXPECT_EQ(board.reset_flags() & (kExtrf | kBorf | kWdrf), kBorf);
  EXPECT_EQ(board.TakeResets(), std::vector<std::string>{"a brown-out"});
  ASSERT_EQ(board.RunUntil(40 * kCyclesPerMs), "");
  EXPECT_TRUE(board.receiver_on());  // booted again
  board.Reset(AvrBoard::ResetCause::kExternal);
  EXPECT_EQ(board.TakeResets(), std::vector<std::string>{"its reset pin"});
}

TEST(AvrBoardTest, AResetIsTheBoardsFaultWhenResetsAreFailures) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  AvrBoard board(elf, {.resets_restart = false});
  ASSERT_EQ(board.RunUntil(5 * kCyclesPerMs), "");
  board.Reset(AvrBoard::ResetCause::kExternal);
  EXPECT_EQ(board.RunUntil(10 * kCyclesPerMs)
                .rfind("the emulated atmega2560 stopped: it was reset by its reset pin at pc ", 0),
            0u)
      << board.fault();
}

TEST(AvrBoardTest, TheImageNamesItsOwnMcuAndClock) {
  FIRMWARE_OR_SKIP(elf, "names_its_mcu");
  AvrBoard board(elf, {.mcu = "atmega2560", .f_cpu_hz = 16000000});
  const AvrBoardStats s = board.stats();
  EXPECT_EQ(s.mcu, "atmega328p");
  EXPECT_EQ(s.f_cpu_hz, 8000000u);
  EXPECT_EQ(s.sram_bytes, 2048u);
  ASSERT_EQ(board.RunUntilTime(0.5), "");
  EXPECT_NEAR(board.stats().emulated_s(), 0.5, 1e-6);
}

TEST(AvrBoardTest, NoImageIsAnInputError) {
  EXPECT_THROW(AvrBoard("/nonexistent/firmware.elf", {}), InputError);
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  EXPECT_THROW(AvrBoard(elf, {.mcu = "atmega9999"}), InputError) << "no such part";
}

TEST(AvrBoardTest, AnImageLargerThanThePartsFlashIsAnInputError) {
  FIRMWARE_OR_SKIP(elf, "lockstep_robot");  // a Mega 2560 sketch of more than 4 KiB
  // the ATtiny25 has 2 KiB of flash (its datasheet); simavr itself would abort the process
  try {
    AvrBoard board(elf, {.mcu = "attiny25"});
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not fit the 2048 bytes of flash of the attiny25"),
              std::string::npos)
        << e.what();
  }
}

// found by hand: simavr's loader itself crashes on such an image, so it is refused before
TEST(AvrBoardTest, LockBitsWithoutFusesAreAnInputError) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  const std::string dir = testing::FreshDirectory("avr_lock_bits");
  WriteTextFile(dir + "/lock", "\xff");
  const std::string locked = dir + "/locked.elf";
  if (std::system(("avr-objcopy --add-section .lock=" + dir + "/lock " + elf + " " + locked +
                   " 2> /dev/null")
                      .c_str()) != 0) {
    GTEST_SKIP() << "no avr-objcopy (binutils-avr)";
  }
  try {
    AvrBoard board(locked, {});
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lock bits (.lock) without fuses (.fuse)"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

// under the sanitizer build, also that the refused MCU is freed and forgotten
TEST(AvrBoardTest, APartWithoutAUartIsAnInputErrorAndTheNextBoardRuns) {
  FIRMWARE_OR_SKIP(elf, "rx_overflow");  // 292 bytes: it fits the 8 KiB of an ATtiny85
  try {
    AvrBoard board(elf, {.mcu = "attiny85"});
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("attiny85 has no UART0"), std::string::npos) << e.what();
  }
  AvrBoard board(elf, {});
  EXPECT_EQ(board.RunUntil(kCyclesPerMs), "");
  EXPECT_TRUE(board.receiver_on());
}

TEST(AvrBoardTest, TwoRunsOfOneImageAreTheSame) {
  FIRMWARE_OR_SKIP(elf, "millis_clock");
  std::vector<uint8_t> runs[2];
  uint64_t instructions[2];
  for (int r = 0; r < 2; ++r) {
    AvrBoard board(elf, {});
    for (uint64_t ms = 1; ms <= 500; ++ms) {
      if (ms % 7 == 0) board.Write(std::vector<uint8_t>{1, 2, 3});
      ASSERT_EQ(board.RunUntil(ms * kCyclesPerMs), "");
      board.Read(runs[r]);
    }
    instructions[r] = board.stats().instructions;
  }
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_EQ(instructions[0], instructions[1]);
  EXPECT_FALSE(runs[0].empty());
}

}  // namespace
}  // namespace unimouse::link
