// SPDX-License-Identifier: GPL-3.0-or-later
// The emulated board as a transport (avr:PATH.elf): the firmware image runs on an emulated ATmega
// inside this process, and the link runs it for each step's share of cycles.
#include <string>

#include "avr_board.h"
#include "transport.h"

namespace unimouse::link {
namespace {

class AvrTransport final : public Transport {
 public:
  AvrTransport(const std::string& path, const AvrBoard::Options& options)
      : path_(path), board_(path, options) {}

  void Read(std::vector<uint8_t>& out) override { board_.Read(out); }
  // the board only moves when it is run: there is never more to wait for
  bool WaitReadable(std::chrono::milliseconds) override { return false; }
  size_t Write(std::span<const uint8_t> bytes) override {
    board_.Write(bytes);
    return bytes.size();
  }
  bool Connected() const override { return board_.receiver_on(); }
  std::string Describe() const override {
    const AvrBoardStats s = board_.stats();
    char clock[32];
    std::snprintf(clock, sizeof(clock), "%g MHz", s.f_cpu_hz / 1e6);
    return "emulated " + s.mcu + " at " + clock + " running " + path_;
  }
  std::string RunUntil(double time_s) override {
    // the board never goes back: when the simulation starts again, its time runs on
    if (time_s < last_s_) offset_s_ += last_s_;
    last_s_ = time_s;
    return board_.RunUntilTime(offset_s_ + time_s);
  }
  bool clocked() const override { return true; }
  std::string Summary() const override { return board_.stats().Describe(); }

 private:
  std::string path_;
  AvrBoard board_;
  double last_s_ = 0, offset_s_ = 0;
};

}  // namespace

std::unique_ptr<Transport> OpenAvrBoard(const std::string& path, const std::string& mcu,
                                        double f_cpu_hz) {
  AvrBoard::Options options;
  options.mcu = mcu;
  options.f_cpu_hz = static_cast<uint32_t>(f_cpu_hz);
  return std::make_unique<AvrTransport>(path, options);
}

}  // namespace unimouse::link
