// SPDX-License-Identifier: GPL-3.0-or-later
// An InvenSense MPU-6500 (or ICM-20602) on the emulated board's SPI bus: the register map a
// driver uses, so that a firmware's own driver, written with Arduino's SPI library, runs
// unchanged. The values it serves are the IMU component's (the link hands them over every
// step): one model, two faces. The chip answers while its chip-select pin is low; the first
// byte is the register address with bit 7 set for a read, and each further byte reads or writes
// the next register. Modelled: WHO_AM_I, PWR_MGMT_1 (reset, sleep), SMPLRT_DIV, CONFIG,
// GYRO_CONFIG and ACCEL_CONFIG (the full-scale range the firmware selects sets the sensitivity),
// the data registers 0x3B-0x48 (big-endian, latched when the chip is selected), the chip's
// start-up times. Not modelled: the FIFO, interrupts, self-test, offsets, I2C, the DLPF and
// sample rate the registers select (the IMU component's figures apply).
#ifndef UNIMOUSE_TRANSPORT_SPI_IMU_H_
#define UNIMOUSE_TRANSPORT_SPI_IMU_H_

#include <array>
#include <cstdint>
#include <string>

#include "transport.h"

struct avr_t;
struct avr_irq_t;

namespace unimouse::link {

/// What the chip measures now, in SI units, in its own axes.
struct ImuReading {
  double gyro_rad_s[3] = {0, 0, 0};
  double accel_m_s2[3] = {0, 0, 0};
};

class SpiImu {
 public:
  /// Wires the chip to `avr`'s SPI and to the chip-select `pin` ("PB0", low selects).
  SpiImu(avr_t* avr, const std::string& part, const std::string& pin);
  SpiImu(const SpiImu&) = delete;
  SpiImu& operator=(const SpiImu&) = delete;

  void SetReading(const ImuReading& reading) { reading_ = reading; }
  /// Bytes exchanged, register writes above the 1 MHz the part allows for them, transfers while
  /// the chip was not yet up, for the run's last line.
  uint64_t bytes() const { return bytes_; }
  uint64_t fast_writes() const { return fast_writes_; }
  uint64_t early_transfers() const { return early_transfers_; }
  /// Seconds the bytes would keep a real bus busy at the clock the firmware set for each.
  double bus_s() const { return bus_s_; }

 private:
  static void OnSelect(avr_irq_t* irq, uint32_t value, void* param);
  static void OnByte(avr_irq_t* irq, uint32_t value, void* param);
  void Reset();
  double Now_s() const;
  double ClockHz() const;
  uint8_t Register(uint8_t address) const;
  void Write(uint8_t address, uint8_t value);
  void Latch();

  avr_t* avr_;
  avr_irq_t* miso_ = nullptr;
  std::string part_;
  uint8_t who_am_i_;
  uint8_t power_on_reset_;  // PWR_MGMT_1 after power-on or a reset
  std::array<uint8_t, 128> registers_{};
  std::array<uint8_t, 14> latched_{};  // 0x3B-0x48 as the chip was selected
  ImuReading reading_;
  bool selected_ = false;
  bool first_byte_ = true;
  bool reading_mode_ = false;
  uint8_t address_ = 0;
  uint8_t next_out_ = 0;  // what the chip shifts out during the next transfer
  double awake_since_s_ = 0;
  uint64_t bytes_ = 0, fast_writes_ = 0, early_transfers_ = 0;
  double bus_s_ = 0;
};

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_SPI_IMU_H_
