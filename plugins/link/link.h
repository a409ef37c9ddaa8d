// SPDX-License-Identifier: GPL-3.0-or-later
// The hardware-in-the-loop link (docs/protocol.md): the simulator's side of the byte protocol of
// the original UnimouseSim. Every step it reads the firmware's frames (data frames into the
// signals its receive table names, manager bytes, log lines, debug frames), then sends the data
// frames its send table lists, each at its period; the defaults are the original's encoder and
// ToF frames and motor commands. Extensions the firmware can ask for: lock-step (a clock frame
// after each step's frames, then the simulator waits for the firmware's step-done byte) and
// debug channels. Failsafe: a lost link (port gone, peer closed, process ended) sets every
// received signal (the motors) to 0; so does silence for failsafe_s, but only from firmware
// that said it repeats its commands (manager 0x12, or lock-step): the original's firmware sent
// commands only when they changed, and its silence holds the last ones, as the original did.
#ifndef UNIMOUSE_PLUGINS_LINK_LINK_H_
#define UNIMOUSE_PLUGINS_LINK_LINK_H_

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "frame_codec.h"
#include "frame_table.h"
#include "transport.h"
#include "unimouse/component.h"

namespace unimouse::link {

struct LinkParams {
  std::string transport = kDefaultTransportSpec;
  std::string send = kOriginalSend;
  std::string receive = kOriginalReceive;
  double tof_full_scale_m = UNIMOUSE_TOF_FULL_SCALE_M;
  double failsafe_s = 0.1;
  double lockstep_timeout_s = 5;
  int baud = 0;
  int queue_bytes = 1024;
  std::string beliefs_out = "firmware_beliefs.json";
  std::string profile = "unimouse";
  bool extensions = true;
  param::GivenSet given;
  param::GivenSet from_data_file;
  std::string mcu = "atmega2560";
  double f_cpu_hz = 16000000;
  std::string spi_imu;
  std::string spi_imu_cs_pin = "PB0";
  std::string spi_imu_from = "imu";
  int max_restarts = 100;
  double wait_for_firmware_s = 0;
  std::string board_reset = "restart";
  double reset_at_s = 0;
  std::string reset_cause = "external";

  template <class V>
  void Visit(V& v) {
    v("transport", transport, TransportUsages());
    v("send", send,
      "frames sent each step, in this order: entries 'ID SIGNAL ENCODING [PERIOD_S]' separated "
      "by ';'; ENCODING tof, i16 or f32; PERIOD_S in seconds, a whole number of the link's "
      "steps, 0 or omitted for every step");
    v("receive", receive,
      "frames that write signals: entries 'ID SIGNAL ENCODING' separated by ';'; ENCODING "
      "motor (int16 within +-1023), i16 or f32");
    v("tof_full_scale_m", tof_full_scale_m,
      "distance a tof frame sends as 0xFFFF, and its scale (table 3.8)", param::Positive{});
    v("failsafe_s", failsafe_s,
      "silence after which every received signal (the motors) is set to 0, for firmware that "
      "said it repeats its commands (manager 0x12, or lock-step); 0 turns it off. A lost link "
      "always stops the motors",
      param::NonNegative{});
    v("lockstep_timeout_s", lockstep_timeout_s,
      "how long lock-step waits for the firmware before giving up", param::Positive{});
    v("baud", baud,
      "release bytes no faster than this line would (10 bits a byte, eq. 4.1); 0: as fast as "
      "the transport takes them, or a serial port's own rate",
      param::Range{0, 10000000});
    v("queue_bytes", queue_bytes, "bytes waiting to go out at most; frames beyond are dropped",
      param::Range{16, 1 << 20});
    v("beliefs_out", beliefs_out,
      "file in the run's output directory for what the firmware reported on its debug "
      "channels (walls, visited cells, path); empty for none");
    v("profile", profile,
      "what the firmware expects: unimouse (this project's library), or unimousesim-0.1 "
      "(firmware built against the original's library: tof_full_scale_m 1.0, failsafe_s 0, "
      "extensions false, unless given)",
      param::OneOf{"unimouse|unimousesim-0.1"});
    v("extensions", extensions,
      "answer the extension manager codes (lock-step, 'I repeat my commands'); false: the "
      "original's protocol only, they are ignored");
    v("mcu", mcu,
      "the emulated board's part, unless the image names its own (simavr's AVR_MCU section)",
      param::OneOf{"atmega2560|atmega328p"});
    v("f_cpu_hz", f_cpu_hz, "the emulated board's clock, unless the image names its own",
      param::Range{1e6, 32e6});
    v("spi_imu", spi_imu,
      "an IMU chip on the emulated board's SPI bus, mpu6500 or icm20602, serving the values of "
      "the unimouse.imu named by spi_imu_from; empty: none");
    v("spi_imu_cs_pin", spi_imu_cs_pin,
      "the SPI IMU's chip-select pin, port and bit (PB0 is "
      "the Mega 2560's SS, Arduino pin 53)");
    v("spi_imu_from", spi_imu_from, "prefix of the IMU signals the SPI IMU serves");
    v("max_restarts", max_restarts,
      "restarts of the firmware, board resets or reconnections a run takes; one more ends it "
      "(a firmware that keeps resetting, a client that keeps dialling)",
      param::Range{1, 1000000});
    v("wait_for_firmware_s", wait_for_firmware_s,
      "the run's clock starts when the firmware's start-up frames (this project's begin()) "
      "come, waiting up to this long on the wall clock; the bytes before them (a bootloader's, "
      "a reset's noise) are counted and skipped; 0: no wait, every byte is read as frames "
      "(firmware written for the original sends no start-up frames)",
      param::Range{0, 600});
    v("board_reset", board_reset,
      "what the emulated board does when it is reset (watchdog, reset_at_s): restart (the "
      "firmware boots again and the run goes on, as on a board) or fail (the run ends with "
      "exit code 3, for grading)",
      param::OneOf{"restart|fail"});
    v("reset_at_s", reset_at_s,
      "the emulated board is reset at this simulated time, as by its reset button or a "
      "brown-out (reset_cause); 0: never",
      param::NonNegative{});
    v("reset_cause", reset_cause,
      "what reset_at_s is, as the firmware reads it in MCUSR: external (the reset button) or "
      "brownout",
      param::OneOf{"external|brownout"});
  }
};

class Link final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.link";
  static constexpr const char* kSummary = "hardware-in-the-loop link to a firmware";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = LinkParams;

  /// Most bytes read from the firmware in one step; the rest waits for the next one.
  static constexpr size_t kReadPerStep_bytes = 64 * 1024;
  /// Bytes a firmware may send in a run, plus kFloodRate_bytes_per_s for every simulated
  /// second, before it counts as flooding the link, which ends the run: no firmware talks that
  /// much (a 115200 baud line carries 11.5 kB a second, a 1 Mbaud one 100 kB).
  static constexpr uint64_t kFloodAllowance_bytes = 1 << 20;
  static constexpr uint64_t kFloodRate_bytes_per_s = 1 << 20;

  /// Reads the frame tables; throws InputError naming a wrong entry. Opens nothing.
  explicit Link(Params params);
  ~Link() override;
  void Bind(BindContext& ctx) override;
  /// Opens the transport: a port, a server, or the firmware process.
  void Start() override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;
  void Finish(const SenseContext& ctx) const override;

 private:
  // what the firmware said during one step that the step waits for
  struct Heard {
    bool lockstep_on = false;
    bool step_done = false;
    bool gone_or_restarted = false;  // the firmware that owed this step is not there any more
  };
  struct Outgoing {
    TableEntry entry;
    SignalId signal;
    int every_n_steps = 1;
  };
  struct Incoming {
    TableEntry entry;
    SignalId signal;
  };

  // reads what the transport has, within this step's budget, and applies its frames
  void Receive(const SenseContext& ctx, Heard& heard) const;
  // whether any received signal (a motor) is not 0
  bool Commanded(const SenseContext& ctx) const;
  // ends the run when the firmware crashed or quit (the transport's Failure); returns whether
  bool FailIfFirmwareFailed(const SenseContext& ctx) const;
  // applies bytes read, with the peers that came and went around them
  void ApplyInOrder(const SenseContext& ctx, const std::vector<uint8_t>& bytes, Heard& heard) const;
  // a peer that came or went: logged, counted, and the motors stopped when one goes
  void PeerCame(const SenseContext& ctx) const;
  void PeerLost(const SenseContext& ctx, Heard& heard) const;
  // what a firmware that starts again (a new peer, a board reset) has not said yet: no commands,
  // no lock-step, and its next frame is a restart
  void FirmwareStartsOver(const SenseContext& ctx) const;
  // before the run's clock starts: skips what comes before the firmware's start-up codes, then
  // reads them and the rest; false (after failing the run) when they do not come in time
  bool AwaitStartUp(const SenseContext& ctx, Heard& heard) const;
  // runs a clocked transport (the emulated board) for this step, then reads what it sent
  void RunBoard(const SenseContext& ctx, Heard& heard, bool lockstep) const;
  void Apply(const SenseContext& ctx, const FirmwareFrame& frame, Heard& heard) const;
  // waits for the firmware, reading, until heard.*until; false (after failing the run) when it
  // does not come within lockstep_timeout_s
  bool AwaitFirmware(const SenseContext& ctx, Heard& heard, bool Heard::*until,
                     const char* waiting_for) const;
  // logs what the firmware printed outside the protocol since the last call
  void TakeText(const SenseContext& ctx) const;
  // queues frames and releases them no faster than the line's baud rate
  void Send(const SenseContext& ctx, const std::string& frames, bool lockstep) const;
  // every signal the firmware writes back to 0, as after a stop or a silence
  void ZeroReceived(const TickContext& ctx) const;
  const Incoming* FindIncoming(uint8_t id) const;
  // follows the frames for a firmware starting over: its start-up codes again, or the first
  // frame after the link came back
  void WatchForRestart(const SenseContext& ctx, const FirmwareFrame& f, Heard& heard) const;
  // the firmware started over: motors stopped, lock-step off until it asks again
  void Restarted(const SenseContext& ctx, const char* sign, Heard& heard) const;
  // counts one more restart, board reset or reconnection; false (after failing the run) past
  // max_restarts
  bool WithinRestarts(const SenseContext& ctx, uint64_t count, const char* what) const;

  const Params p_;
  std::vector<Outgoing> send_;
  std::vector<Incoming> receive_;
  std::vector<DataFrame> data_frames_;  // the receive table, as the decoder reads it
  int physics_steps_per_step_ = 1;
  double period_s_ = 0;
  // lock-step on a clocked board: steps it did not finish within its cycles, and when it last did
  mutable uint64_t late_steps_ = 0;
  mutable double last_step_done_s_ = 0;
  double bytes_per_step_ = 0;
  std::string beliefs_path_;
  BindContext::MazeInfo maze_;   // what a firmware is told when it asks for the maze
  int traits_ = 0;               // what the link is to the run (UNIMOUSE_TRAIT_*)
  int spec_baud_ = 0;            // the line rate the transport spec names, 0 for none
  double send_bytes_per_s_ = 0;  // what the send table needs at its periods
  SignalId imu_[6];              // the SPI IMU's gyro x y z, accel x y z, when there is one
  // the connection is a resource, opened by Start, never part of a snapshot
  std::unique_ptr<Transport> transport_;

  // what the link holds between steps; Reset clears all of it
  mutable FrameDecoder decoder_;
  mutable std::vector<uint8_t> inbox_;
  mutable std::vector<std::string> text_;  // lines printed outside the protocol, this read
  mutable bool text_said_ = false;         // whether the log said that plain text comes
  mutable size_t read_this_step_ = 0;
  mutable uint64_t received_bytes_ = 0;  // since the last reset
  mutable bool was_connected_ = false;
  mutable uint64_t peers_seen_ = 0;  // the transport's count of peers when last looked at
  // restarts: frames since the run began, whether this firmware sent its start-up codes, how
  // many of them just came in a row, whether the next frame is a new firmware's (the link came
  // back), and the counts
  mutable uint64_t frames_ever_ = 0;
  mutable bool begun_ = false;
  mutable size_t startup_codes_in_a_row_ = 0;
  mutable bool next_frame_restarts_ = false;
  mutable uint64_t restarts_ = 0;
  mutable uint64_t board_resets_ = 0;
  mutable uint64_t reconnections_ = 0;
  mutable uint64_t skipped_before_start_up_ = 0;  // bytes before the start-up codes, waiting
  // what the firmware says it believes, for the run's maze picture
  struct Beliefs {
    std::map<std::pair<int, int>, std::pair<int, int>> walls;  // cell -> walls, known
    std::vector<std::pair<int, int>> visited;
    std::vector<std::pair<int, int>> path;
  };
  mutable Beliefs beliefs_;
  // bytes waiting for the line, the line's budget, and what did not fit
  mutable std::string queue_;
  mutable double budget_bytes_ = 0;
  mutable uint64_t dropped_bytes_ = 0;
};

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_LINK_H_
