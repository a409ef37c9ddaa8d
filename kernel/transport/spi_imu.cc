// SPDX-License-Identifier: GPL-3.0-or-later
#include "spi_imu.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "avr_ioport.h"
#include "avr_spi.h"
#include "imu.h"
#include "sim_avr.h"
#include "sim_io.h"
#include "sim_irq.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

// the register map (MPU-6500 register map and descriptions; the ICM-20602's is the same here)
constexpr uint8_t kSmplrtDiv = 0x19;
constexpr uint8_t kConfig = 0x1A;
constexpr uint8_t kGyroConfig = 0x1B;
constexpr uint8_t kAccelConfig = 0x1C;
constexpr uint8_t kAccelXoutH = 0x3B;  // 14 data registers: accel x y z, temperature, gyro x y z
constexpr uint8_t kPwrMgmt1 = 0x6B;
constexpr uint8_t kWhoAmI = 0x75;
constexpr uint8_t kDeviceReset = 0x80;
constexpr uint8_t kSleep = 0x40;

// times from the datasheets' electrical characteristics (maxima): registers answer 100 ms after
// power-up; the gyro gives data 35 ms after it wakes
constexpr double kRegisterStartup_s = 0.100;
constexpr double kGyroStartup_s = 0.035;
// register writes are specified up to 1 MHz of SPI clock (sensor reads up to 20 MHz)
constexpr double kMaxWriteClock_hz = 1e6;

constexpr double kStandardGravity_m_s2 = 9.80665;
// the temperature register at 25 degC: (T - 21) * 333.87
constexpr int kTemperature25C = 1335;

// the ATmega's SPI registers in data space, for the clock the firmware set
constexpr int kSpcr = 0x4C;
constexpr int kSpsr = 0x4D;

int16_t Counts(double value, double counts_per_unit) {
  return static_cast<int16_t>(std::clamp(std::round(value * counts_per_unit), -32768.0, 32767.0));
}

}  // namespace

SpiImu::SpiImu(avr_t* avr, const std::string& part, const std::string& pin)
    : avr_(avr),
      part_(part),
      who_am_i_(part == "icm20602" ? 0x12 : 0x70),
      // the ICM-20602 powers up asleep; the MPU-6500 awake, on its internal clock
      power_on_reset_(part == "icm20602" ? 0x41 : 0x01) {
  UNIMOUSE_THROW_UNLESS(SpiImuPartProblem(part).empty(), SpiImuPartProblem(part));
  Reset();
  awake_since_s_ = (registers_[kPwrMgmt1] & kSleep) ? INFINITY : 0;
  // simavr names a part's only SPI 0, and the first of several '0'
  const char name = avr_io_getirq(avr_, AVR_IOCTL_SPI_GETIRQ(0), SPI_IRQ_INPUT) ? 0 : '0';
  miso_ = avr_io_getirq(avr_, AVR_IOCTL_SPI_GETIRQ(name), SPI_IRQ_INPUT);
  avr_irq_t* mosi = avr_io_getirq(avr_, AVR_IOCTL_SPI_GETIRQ(name), SPI_IRQ_OUTPUT);
  avr_irq_t* select = avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ(pin[1]), pin[2] - '0');
  UNIMOUSE_THROW_UNLESS(miso_ && mosi && select, "the emulated MCU has no SPI or no pin " + pin);
  avr_irq_register_notify(mosi, &SpiImu::OnByte, this);
  avr_irq_register_notify(select, &SpiImu::OnSelect, this);
}

void SpiImu::Reset() {
  registers_.fill(0);
  registers_[kPwrMgmt1] = power_on_reset_;
  registers_[kWhoAmI] = who_am_i_;
  latched_.fill(0);
}

double SpiImu::Now_s() const {
  return static_cast<double>(avr_->cycle) / static_cast<double>(avr_->frequency);
}

void SpiImu::OnSelect(avr_irq_t*, uint32_t value, void* param) {
  auto* self = static_cast<SpiImu*>(param);
  const bool selected = value == 0;
  if (selected && !self->selected_) {
    self->first_byte_ = true;
    self->next_out_ = 0;
    self->Latch();
  }
  self->selected_ = selected;
}

void SpiImu::Latch() {
  // the data registers hold the last sample while the chip sleeps, and zeros until the gyro
  // has started
  if (registers_[kPwrMgmt1] & kSleep) return;
  if (Now_s() - awake_since_s_ < kGyroStartup_s) {
    latched_.fill(0);
    return;
  }
  // FS_SEL and AFS_SEL pick +-250 dps and +-2 g, doubled per step: the part's table is the imu
  // component's
  const double gyro = plugins::GyroSensitivity(part_, 250 << ((registers_[kGyroConfig] >> 3) & 3)) *
                      180 / std::numbers::pi;
  const double accel =
      plugins::AccelSensitivity(part_, 2 << ((registers_[kAccelConfig] >> 3) & 3)) /
      kStandardGravity_m_s2;
  int16_t words[7];
  for (int i = 0; i < 3; ++i) {
    words[i] = Counts(reading_.accel_m_s2[i], accel);
    words[4 + i] = Counts(reading_.gyro_rad_s[i], gyro);
  }
  words[3] = kTemperature25C;
  for (int i = 0; i < 7; ++i) {
    latched_[2 * i] = static_cast<uint8_t>(static_cast<uint16_t>(words[i]) >> 8);
    latched_[2 * i + 1] = static_cast<uint8_t>(words[i] & 0xFF);
  }
}

uint8_t SpiImu::Register(uint8_t address) const {
  if (address >= kAccelXoutH && address < kAccelXoutH + 14) return latched_[address - kAccelXoutH];
  return registers_[address & 0x7F];
}

void SpiImu::Write(uint8_t address, uint8_t value) {
  switch (address) {
    case kPwrMgmt1:
      if (value & kDeviceReset) {
        Reset();
        awake_since_s_ = (registers_[kPwrMgmt1] & kSleep) ? INFINITY : Now_s();
        return;
      }
      if ((registers_[kPwrMgmt1] & kSleep) && !(value & kSleep)) awake_since_s_ = Now_s();
      if (value & kSleep) awake_since_s_ = INFINITY;
      registers_[address] = value;
      return;
    case kWhoAmI:
      return;  // read-only
    default:
      // the data registers are read-only; the rest keep what is written (SMPLRT_DIV, CONFIG,
      // GYRO_CONFIG, ACCEL_CONFIG, ...), whether or not the model acts on it
      if (address >= kAccelXoutH && address < kAccelXoutH + 14) return;
      registers_[address & 0x7F] = value;
  }
}

double SpiImu::ClockHz() const {
  // the clock the firmware set: f / 4, 16, 64 or 128 (SPR1:0), doubled by SPI2X
  static constexpr int kDividers[4] = {4, 16, 64, 128};
  const double hz = static_cast<double>(avr_->frequency) / kDividers[avr_->data[kSpcr] & 3];
  return avr_->data[kSpsr] & 1 ? 2 * hz : hz;
}

void SpiImu::OnByte(avr_irq_t*, uint32_t value, void* param) {
  auto* self = static_cast<SpiImu*>(param);
  if (!self->selected_) return;
  ++self->bytes_;
  // what the byte would keep a real bus busy for at that clock (simavr takes 100 us whatever)
  self->bus_s_ += 8 / self->ClockHz();
  // before its registers are up the chip does not drive MISO: the MCU reads 0x00 (the emulated
  // line; on a board an undriven MISO reads whatever the line floats to)
  if (self->Now_s() < kRegisterStartup_s) {
    ++self->early_transfers_;
    return;
  }
  const auto byte = static_cast<uint8_t>(value);
  const uint8_t out = self->next_out_;
  if (self->first_byte_) {
    self->first_byte_ = false;
    self->reading_mode_ = (byte & 0x80) != 0;
    self->address_ = byte & 0x7F;
  } else if (!self->reading_mode_) {
    if (self->ClockHz() > kMaxWriteClock_hz) ++self->fast_writes_;
    self->Write(self->address_, byte);
    self->address_ = (self->address_ + 1) & 0x7F;
  } else {
    self->address_ = (self->address_ + 1) & 0x7F;
  }
  // a read shifts out the register at the address during the next transfer
  if (self->reading_mode_) self->next_out_ = self->Register(self->address_);
  avr_raise_irq(self->miso_, out);
}

}  // namespace unimouse::link
