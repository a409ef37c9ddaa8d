// SPDX-License-Identifier: GPL-3.0-or-later
// The hardware-in-the-loop link (docs/protocol.md): the simulator's side of the byte protocol of
// the original UnimouseSim. Every step it reads the firmware's frames (motor commands into the
// H-bridge inputs, manager bytes, log lines, debug frames), then sends encoder frames every step
// and ToF frames every 30 ms. Extensions the firmware can ask for: lock-step (a clock frame
// after each step's frames, then the simulator waits for the firmware's step-done byte) and
// debug channels. Failsafe: when no frame arrives for failsafe_s, both commands fall to 0.
#ifndef UNIMOUSE_PLUGINS_LINK_LINK_H_
#define UNIMOUSE_PLUGINS_LINK_LINK_H_

#include <map>
#include <memory>
#include <string>

#include "frame_codec.h"
#include "transport.h"
#include "unimouse/component.h"

namespace unimouse::link {

struct LinkParams {
  std::string transport = "pty";
  std::string tof_left = "tof.left_m";
  std::string tof_right = "tof.right_m";
  std::string tof_front = "tof.front_m";
  std::string encoder_left = "left.encoder_counts";
  std::string encoder_right = "right.encoder_counts";
  std::string motor_left = "left.command";
  std::string motor_right = "right.command";
  double tof_full_scale_m = UNIMOUSE_TOF_FULL_SCALE_M;
  double tof_period_s = 0.03;
  double failsafe_s = 0.1;
  double lockstep_timeout_s = 5;
  bool start_with_lockstep = false;
  int baud = 0;
  int queue_bytes = 1024;
  std::string lockstep_out = "link.lockstep";
  std::string beliefs_out = "firmware_beliefs.json";
  std::string mcu = "atmega2560";
  double f_cpu_hz = 16000000;

  template <class V>
  void Visit(V& v) {
    v("transport", transport,
      "pty, pty:LINK, serial:PATH@BAUD, tcp::PORT, native:PROGRAM or avr:PATH.elf");
    v("tof_left", tof_left, "signal sent as frame 0: left ToF reading, metres");
    v("tof_right", tof_right, "signal sent as frame 1: right ToF reading, metres");
    v("tof_front", tof_front, "signal sent as frame 2: front ToF reading, metres");
    v("encoder_left", encoder_left, "signal sent as frame 3: left encoder counts per step");
    v("encoder_right", encoder_right, "signal sent as frame 4: right encoder counts per step");
    v("motor_left", motor_left, "signal it writes from frame 5: left H-bridge command");
    v("motor_right", motor_right, "signal it writes from frame 6: right H-bridge command");
    v("tof_full_scale_m", tof_full_scale_m, "distance sent as 0xFFFF (table 3.8)",
      param::Positive{});
    v("tof_period_s", tof_period_s, "how often ToF frames go out", param::Positive{});
    v("failsafe_s", failsafe_s,
      "silence after which the motors are stopped; 0 turns the failsafe off, for firmware "
      "that sends commands only when they change",
      param::NonNegative{});
    v("lockstep_timeout_s", lockstep_timeout_s,
      "how long lock-step waits for the firmware before giving up", param::Positive{});
    v("baud", baud,
      "release bytes no faster than this line would (10 bits a byte, eq. 4.1); 0: as fast as "
      "the transport takes them, or a serial port's own rate",
      param::Range{0, 10000000});
    v("queue_bytes", queue_bytes, "bytes waiting to go out at most; frames beyond are dropped",
      param::Range{16, 1 << 20});
    v("start_with_lockstep", start_with_lockstep,
      "the first step waits until the firmware asks for lock-step, so that runs are identical "
      "from step 0; for firmware the simulator starts itself");
    v("beliefs_out", beliefs_out,
      "file in the run's output directory for what the firmware reported on its debug "
      "channels (walls, visited cells, path); empty for none");
    v("lockstep_out", lockstep_out,
      "signal it writes: 1 once the firmware runs in lock-step (the run stops pacing then)");
    v("mcu", mcu,
      "avr: the emulated part, unless the image names its own (simavr's AVR_MCU section)",
      param::OneOf{"atmega2560|atmega328p"});
    v("f_cpu_hz", f_cpu_hz, "avr: the emulated clock, unless the image names its own",
      param::Range{1e6, 32e6});
  }
};

class Link final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.link";
  static constexpr const char* kSummary = "hardware-in-the-loop link over pty, serial or TCP";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = LinkParams;

  explicit Link(Params params);
  ~Link() override;
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;
  void Finish(const SenseContext& ctx) const override;

  const Transport& transport() const { return *transport_; }

 private:
  void Receive(const SenseContext& ctx, bool* step_done) const;
  // queues frames and releases them no faster than the line's baud rate
  void Send(const SenseContext& ctx, const std::string& frames, bool lockstep) const;
  // waits for the firmware until `done` holds; false (after reporting why) on timeout
  bool AwaitFirmware(const SenseContext& ctx, bool* step_done, const char* waiting_for) const;
  void Apply(const SenseContext& ctx, const FirmwareFrame& frame, bool* step_done) const;

  const Params p_;
  SignalId tof_[3], encoder_[2], motor_[2], lockstep_;
  int tof_every_n_steps_ = 30;
  // the connection is a resource, rebuilt on load, never part of a snapshot
  std::unique_ptr<Transport> transport_;
  mutable FrameDecoder decoder_;
  mutable std::vector<uint8_t> inbox_;
  mutable bool was_connected_ = false;
  // what the firmware says it believes, for the run's maze picture
  struct Beliefs {
    std::map<std::pair<int, int>, std::pair<int, int>> walls;  // cell -> walls, known
    std::vector<std::pair<int, int>> visited;
    std::vector<std::pair<int, int>> path;
  };
  mutable Beliefs beliefs_;
  std::string beliefs_path_;
  // bytes waiting for the line, the line's budget, and what did not fit
  mutable std::string queue_;
  mutable double budget_bytes_ = 0;
  mutable uint64_t dropped_bytes_ = 0;
  double bytes_per_step_ = 0;
  double period_s_ = 0;
  // lock-step on a clocked board: steps it did not finish within its cycles, and when it last did
  mutable uint64_t late_steps_ = 0;
  mutable double last_step_done_s_ = 0;
};

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_LINK_H_
