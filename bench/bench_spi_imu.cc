// SPDX-License-Identifier: GPL-3.0-or-later
// What the MPU-6500 on the emulated board's SPI bus costs the emulation: the test driver
// (tests/avr/imu_spi.ino, which reads gyro z over SPI every millisecond) on two emulated Mega
// 2560s side by side, one with the chip on its bus and one without (its reads then return 0;
// simavr times SPI bytes alike either way, so both run the same cycles). They take turns 100 ms
// of emulated time at a time, and each one's host CPU time is summed.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "avr_board.h"
#include "spi_imu.h"

namespace {

using namespace unimouse;

const std::string kSpiImage = UNIMOUSE_BINARY_DIR "/tests/avr/imu_spi.elf";

void BM_AvrBoardSpiImuSideBySide(benchmark::State& bench) {
  if (!std::filesystem::exists(kSpiImage)) {
    bench.SkipWithError("no AVR test firmware (gcc-avr, arduino-core-avr)");
    return;
  }
  double with_mhz = 0, without_mhz = 0;
  for (auto _ : bench) {
    link::AvrBoard with(kSpiImage, {});
    link::AvrBoard without(kSpiImage, {});
    link::SpiImu chip(with.mcu(), "mpu6500", "PB0");
    link::ImuReading reading;
    reading.accel_m_s2[2] = 9.81;
    chip.SetReading(reading);
    // 3 emulated seconds each, 100 ms in turn
    for (int chunk = 1; chunk <= 30; ++chunk) {
      const uint64_t cycle = static_cast<uint64_t>(chunk) * 1600000;
      if (!with.RunUntil(cycle).empty() || !without.RunUntil(cycle).empty()) {
        bench.SkipWithError("the firmware stopped");
        return;
      }
    }
    with_mhz = with.stats().emulated_mhz();
    without_mhz = without.stats().emulated_mhz();
    bench.counters["spi_bytes"] = static_cast<double>(chip.bytes());
  }
  bench.counters["with_chip_emulated_mhz"] = with_mhz;
  bench.counters["without_chip_emulated_mhz"] = without_mhz;
  bench.counters["speed_with_chip_percent"] = 100 * with_mhz / without_mhz;
}
BENCHMARK(BM_AvrBoardSpiImuSideBySide)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
