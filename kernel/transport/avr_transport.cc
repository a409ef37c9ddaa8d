// SPDX-License-Identifier: GPL-3.0-or-later
// The emulated board (avr:PATH.elf): the firmware image runs on an emulated ATmega inside this
// process, and the link runs it for each step's share of cycles instead of waiting for it.
#include <cstdio>
#include <optional>
#include <string>

#include "transport.h"
#include "unimouse/errors.h"
#ifdef UNIMOUSE_HAVE_SIMAVR
#include "avr_board.h"
#include "spi_imu.h"
#endif

namespace unimouse::link {
#ifdef UNIMOUSE_HAVE_SIMAVR
namespace {

class AvrTransport final : public Transport {
 public:
  explicit AvrTransport(const std::string& path) : path_(path) {
    UNIMOUSE_THROW_UNLESS(!path.empty(), "avr needs a firmware image: avr:PATH.elf");
  }

  // the part and clock are the link's parameters, so the image loads only now
  void Configure(const TransportSettings& settings) override {
    AvrBoard::Options options;
    options.mcu = settings.mcu;
    options.f_cpu_hz = static_cast<uint32_t>(settings.f_cpu_hz);
    options.resets_restart = settings.resets_restart;
    board_.emplace(path_, options);
    reset_at_s_ = settings.reset_at_s;
    reset_cause_ = settings.reset_cause == "brownout" ? AvrBoard::ResetCause::kBrownOut
                                                      : AvrBoard::ResetCause::kExternal;
    if (!settings.spi_imu_part.empty()) {
      imu_.emplace(board_->mcu(), settings.spi_imu_part, settings.spi_imu_cs_pin);
    }
  }
  void SetImuReading(std::span<const double, 6> values) override {
    if (!imu_) return;
    ImuReading reading;
    for (int i = 0; i < 3; ++i) {
      reading.gyro_rad_s[i] = values[i];
      reading.accel_m_s2[i] = values[3 + i];
    }
    imu_->SetReading(reading);
  }
  void Read(std::vector<uint8_t>& out, size_t max_bytes) override {
    if (board_) board_->Read(out, max_bytes);
  }
  // the board only moves when it is run: there is never more to wait for
  bool WaitReadable(std::chrono::milliseconds) override { return false; }
  size_t Write(std::span<const uint8_t> bytes) override {
    if (board_) board_->Write(bytes);
    return bytes.size();
  }
  bool Connected() const override { return board_ && board_->receiver_on(); }
  std::string Describe() const override {
    if (!board_) return "emulated board for " + path_;
    const AvrBoardStats s = board_->stats();
    char clock[32];
    std::snprintf(clock, sizeof(clock), "%g MHz", s.f_cpu_hz / 1e6);
    return "emulated " + s.mcu + " at " + clock + " running " + path_;
  }
  bool clocked() const override { return true; }
  std::string RunUntil(double time_s) override {
    if (!board_) return "";
    // the board never goes back: when the simulation starts again, its time runs on
    if (time_s < last_s_) {
      offset_s_ += last_s_;
      reset_done_ = false;
    }
    last_s_ = time_s;
    // the reset button, pressed at its time of the simulation's clock
    if (reset_at_s_ > 0 && !reset_done_ && reset_at_s_ <= time_s) {
      reset_done_ = true;
      if (std::string fault = board_->RunUntilTime(offset_s_ + reset_at_s_); !fault.empty()) {
        return fault;
      }
      board_->Reset(reset_cause_);
    }
    return board_->RunUntilTime(offset_s_ + time_s);
  }
  std::vector<std::string> TakeResets() override {
    return board_ ? board_->TakeResets() : std::vector<std::string>{};
  }
  std::vector<std::string> TakeNotices() override {
    return board_ ? board_->TakeNotices() : std::vector<std::string>{};
  }
  std::string Summary() const override {
    if (!board_) return "";
    std::string text = board_->stats().Describe();
    if (imu_) {
      char more[240];
      std::snprintf(more, sizeof(more),
                    "; SPI IMU: %llu bytes (%.1f ms of a real bus at the clocks the firmware set), "
                    "%llu register writes above its 1 MHz, %llu transfers before its 100 ms "
                    "start-up",
                    static_cast<unsigned long long>(imu_->bytes()), 1e3 * imu_->bus_s(),
                    static_cast<unsigned long long>(imu_->fast_writes()),
                    static_cast<unsigned long long>(imu_->early_transfers()));
      text += more;
    }
    return text;
  }
  std::vector<std::pair<std::string, double>> Measurements() const override {
    return board_ ? board_->stats().Named() : std::vector<std::pair<std::string, double>>{};
  }

 private:
  std::string path_;
  std::optional<AvrBoard> board_;
  std::optional<SpiImu> imu_;  // after the board: it is wired to the board's MCU
  double last_s_ = 0, offset_s_ = 0;
  double reset_at_s_ = 0;  // 0: never
  AvrBoard::ResetCause reset_cause_ = AvrBoard::ResetCause::kExternal;
  bool reset_done_ = false;
};

}  // namespace

std::unique_ptr<Transport> OpenAvr(const std::string& path) {
  return std::make_unique<AvrTransport>(path);
}
#else
std::unique_ptr<Transport> OpenAvr(const std::string&) {
  throw InputError("avr: this build has no emulated board (it needs libsimavr-dev, libelf-dev)");
}
#endif

}  // namespace unimouse::link
