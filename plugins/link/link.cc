// SPDX-License-Identifier: GPL-3.0-or-later
#include "link.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

// state slots: what the firmware asked for, and when it last spoke
constexpr int kSensorsOn = 0;
constexpr int kLockstep = 1;
constexpr int kLastFrame_s = 2;
constexpr int kFailsafe = 3;
constexpr int kUnknownReported = 4;
constexpr int kRepeats = 5;     // the firmware said it resends its commands
constexpr int kMazeAsked = 6;   // the firmware asked for the maze: it goes out with the next frames
constexpr int kSizesAsked = 7;  // the firmware asked for the data frames' sizes: the same
constexpr int kStateSize = 8;

// the start-up codes of this project's library, in their order (unimouse_protocol.h)
constexpr uint8_t kStartupCodes[] = UNIMOUSE_STARTUP_CODES;
constexpr size_t kStartupCodeCount = sizeof(kStartupCodes);

// visited cells kept for the beliefs file: a firmware that reports more repeats itself
constexpr size_t kMaxVisitedKept = 1 << 20;

// a time for a message, to the millisecond
std::string Seconds(double t_s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", t_s);
  return text;
}

// what firmware built against the original's library expects, where the robot file and the
// command line leave it open
LinkParams WithProfile(LinkParams p) {
  if (p.profile == "unimousesim-0.1") {
    // its library decodes ToF readings at 1.0 m (the examples predate the 1.2 m release), sends
    // a command only when it changes, and knows no extension
    if (!param::Given(p.given, "tof_full_scale_m")) p.tof_full_scale_m = 1.0;
    if (!param::Given(p.given, "failsafe_s")) p.failsafe_s = 0;
    if (!param::Given(p.given, "extensions")) p.extensions = false;
  }
  return p;
}

std::string Sides(uint8_t bits) {
  std::string out;
  const char* names[] = {"N", "E", "S", "W"};
  for (int i = 0; i < 4; ++i) {
    if (bits >> i & 1) out += (out.empty() ? "" : " ") + std::string(names[i]);
  }
  return out.empty() ? "none" : out;
}

}  // namespace

Link::Link(Params params) : p_(WithProfile(std::move(params))) {
  // a robot file is data: it may name a port or a server, never a program to run or a path to
  // make, which only the person running the simulator chooses
  const TransportSpec spec = ParseTransportSpec(p_.transport);
  if (param::Given(p_.from_data_file, "transport")) {
    if (const std::string refused = spec.RefusedInDataFile(); !refused.empty()) {
      throw InputError("transport '" + p_.transport.substr(0, 200) + "' " + refused +
                       ": a robot file may not ask for that; give it on the command line "
                       "(--link) instead");
    }
  }
  // what the run needs to know of the peer, declared at bind
  traits_ = UNIMOUSE_TRAIT_FIRMWARE | (spec.kind->wall_clock ? UNIMOUSE_TRAIT_WALL_CLOCK : 0);
  spec_baud_ = spec.LineBaud();
  if (!p_.spi_imu.empty()) {
    UNIMOUSE_THROW_UNLESS(SpiImuPartProblem(p_.spi_imu).empty(),
                          "spi_imu: " + SpiImuPartProblem(p_.spi_imu));
    UNIMOUSE_THROW_UNLESS(PinProblem(p_.mcu, p_.spi_imu_cs_pin).empty(),
                          "spi_imu_cs_pin: " + PinProblem(p_.mcu, p_.spi_imu_cs_pin));
  }
  // a wrong table is bad input now, before anything is bound or opened
  for (TableEntry& e : ParseSendTable(p_.send)) send_.push_back({std::move(e), {}, 1});
  for (TableEntry& e : ParseReceiveTable(p_.receive)) {
    data_frames_.push_back({e.id, e.encoding});
    receive_.push_back({std::move(e), {}});
  }
  decoder_ = FrameDecoder(data_frames_);
}

Link::~Link() = default;

void Link::Bind(BindContext& ctx) {
  period_s_ = ctx.period_s();
  physics_steps_per_step_ =
      std::max(1, static_cast<int>(std::lround(period_s_ / ctx.timestep_s())));
  for (Outgoing& o : send_) {
    o.signal = ctx.ReadSignal(o.entry.signal);
    o.every_n_steps = StepsPerFrame(o.entry, period_s_);
  }
  std::vector<TableEntry> entries;
  for (const Outgoing& o : send_) entries.push_back(o.entry);
  send_bytes_per_s_ = SendBytesPerSecond(entries, period_s_);
  if (!p_.spi_imu.empty()) {
    const char* names[6] = {".gyro_x_rad_s", ".gyro_y_rad_s", ".gyro_z_rad_s",
                            ".accel_x_m_s2", ".accel_y_m_s2", ".accel_z_m_s2"};
    for (int i = 0; i < 6; ++i) imu_[i] = ctx.ReadSignal(p_.spi_imu_from + names[i]);
  }
  for (Incoming& i : receive_) i.signal = ctx.WriteSignal(i.entry.signal);
  ctx.SetStateSize(kStateSize);
  if (!p_.beliefs_out.empty()) beliefs_path_ = ctx.OutputFile(p_.beliefs_out);
  maze_ = ctx.maze();
  ctx.DeclareTraits(traits_);
}

void Link::Start() {
  transport_ = OpenTransport(p_.transport);
  transport_->Configure({p_.mcu, p_.f_cpu_hz, p_.spi_imu, p_.spi_imu_cs_pin,
                         p_.board_reset == "restart", p_.reset_at_s, p_.reset_cause});
  // a serial port's own rate limits it; other transports go as fast as they are read unless told
  const int baud = p_.baud > 0 ? p_.baud : transport_->line_baud();
  bytes_per_step_ = baud > 0 ? baud / 10.0 * period_s_ : 0;
}

void Link::Reset(const ResetContext& ctx) const {
  std::span<double> s = ctx.state();
  s[kSensorsOn] = 1;  // the original streamed from the start
  s[kLockstep] = 0;
  s[kLastFrame_s] = 0;
  s[kFailsafe] = 0;
  s[kUnknownReported] = 0;
  s[kRepeats] = 0;
  s[kMazeAsked] = 0;
  s[kSizesAsked] = 0;
  ZeroReceived(ctx);
  decoder_ = FrameDecoder(data_frames_);
  inbox_.clear();
  read_this_step_ = 0;
  received_bytes_ = 0;
  was_connected_ = false;
  peers_seen_ = transport_ ? transport_->peers() : 0;  // none before Start
  begun_ = false;
  frames_ever_ = 0;
  startup_codes_in_a_row_ = 0;
  next_frame_restarts_ = false;
  restarts_ = 0;
  board_resets_ = 0;
  reconnections_ = 0;
  skipped_before_start_up_ = 0;
  beliefs_ = {};
  queue_.clear();
  budget_bytes_ = 0;
  dropped_bytes_ = 0;
  late_steps_ = 0;
  last_step_done_s_ = 0;
  if (transport_ != nullptr) ctx.Log("firmware link: " + transport_->Describe());

  // a table the line cannot carry loses frames from the first second: say so before the run,
  // also when the robot file is only checked
  int baud = p_.baud > 0 ? p_.baud : spec_baud_;
  if (baud == 0 && transport_ != nullptr) baud = transport_->line_baud();
  if (baud > 0 && send_bytes_per_s_ > baud / 10.0) {
    char text[320];
    std::snprintf(text, sizeof(text),
                  "the send table needs %.0f bytes a second at its periods, more than the %.0f "
                  "a %d baud line carries (10 bits a byte): frames will be dropped; raise the "
                  "baud rate, or send fewer frames or at longer periods",
                  send_bytes_per_s_, baud / 10.0, baud);
    ctx.Warn(text);
  }
}

void Link::ZeroReceived(const TickContext& ctx) const {
  for (const Incoming& i : receive_) ctx.Write(i.signal, 0);
}

const Link::Incoming* Link::FindIncoming(uint8_t id) const {
  for (const Incoming& i : receive_) {
    if (i.entry.id == id) return &i;
  }
  return nullptr;
}

bool Link::WithinRestarts(const SenseContext& ctx, uint64_t count, const char* what) const {
  if (count <= static_cast<uint64_t>(p_.max_restarts)) return true;
  char text[224];
  std::snprintf(text, sizeof(text), "%s %llu times, more than max_restarts (%d)", what,
                static_cast<unsigned long long>(count), p_.max_restarts);
  ctx.Fail(text);
  return false;
}

void Link::Restarted(const SenseContext& ctx, const char* sign, Heard& heard) const {
  ++restarts_;
  heard.gone_or_restarted = true;
  // a new firmware has said nothing yet: what the last one asked for ends with it, and the
  // original streamed its sensors from the start
  std::span<double> s = ctx.state();
  ZeroReceived(ctx);
  s[kSensorsOn] = 1;
  s[kLockstep] = 0;
  s[kFailsafe] = 0;
  s[kRepeats] = 0;
  ctx.SetFirmwarePaced(false);
  char text[192];
  std::snprintf(text, sizeof(text),
                "the firmware restarted at t=%.3f s (%s): motors stopped until it commands them; "
                "restart %llu",
                ctx.time_s(), sign, static_cast<unsigned long long>(restarts_));
  ctx.Log(text);
  unimouse_report r{};
  r.size = sizeof(r);
  r.kind = UNIMOUSE_REPORT_RESTART;
  r.value = static_cast<double>(restarts_);
  ctx.Report(r);
  WithinRestarts(ctx, restarts_, "the firmware restarted");
}

void Link::WatchForRestart(const SenseContext& ctx, const FirmwareFrame& f, Heard& heard) const {
  ++frames_ever_;
  const bool manager = !f.is_data && f.id == UNIMOUSE_ID_MANAGER;
  if (manager && f.value == kStartupCodes[startup_codes_in_a_row_]) {
    ++startup_codes_in_a_row_;
  } else {
    startup_codes_in_a_row_ = manager && f.value == kStartupCodes[0] ? 1 : 0;
  }
  if (next_frame_restarts_) {
    // any firmware, this project's or not: the first frame on a link that came back
    next_frame_restarts_ = false;
    begun_ = false;
    Restarted(ctx, "its first frame after the link came back", heard);
  }
  if (startup_codes_in_a_row_ == kStartupCodeCount) {
    // this project's library: begin()'s codes a second time (a sketch may send frames before
    // its first begin(), asking for the maze)
    if (begun_) Restarted(ctx, "its start-up frames again", heard);
    begun_ = true;
    startup_codes_in_a_row_ = 0;
  }
}

void Link::Apply(const SenseContext& ctx, const FirmwareFrame& f, Heard& heard) const {
  std::span<double> s = ctx.state();
  WatchForRestart(ctx, f, heard);
  s[kLastFrame_s] = ctx.time_s();
  if (s[kFailsafe] != 0) {
    s[kFailsafe] = 0;
    ctx.Log("the firmware speaks again");
  }
  if (f.is_data) {
    if (const Incoming* in = FindIncoming(f.id)) ctx.Write(in->signal, f.Signal());
    return;
  }
  char text[160];
  const bool extension_code =
      f.id == UNIMOUSE_ID_MANAGER &&
      (f.value == UNIMOUSE_MANAGER_LOCKSTEP_ON || f.value == UNIMOUSE_MANAGER_STEP_DONE ||
       f.value == UNIMOUSE_MANAGER_REPEATS_COMMANDS || f.value == UNIMOUSE_MANAGER_MAZE_INFO);
  if (extension_code && !p_.extensions) {
    std::snprintf(text, sizeof(text),
                  "manager byte 0x%02x ignored: this link speaks the original's protocol only "
                  "(extensions false)",
                  f.value);
    ctx.Warn(text);
    return;
  }
  switch (f.id) {
    case UNIMOUSE_ID_MANAGER:
      switch (f.value) {
        case UNIMOUSE_MANAGER_SENSORS_ON:
        case UNIMOUSE_MANAGER_SENSORS_OFF:
          s[kSensorsOn] = f.value == UNIMOUSE_MANAGER_SENSORS_ON;
          break;
        case UNIMOUSE_MANAGER_STOP:
          ZeroReceived(ctx);
          break;
        case UNIMOUSE_MANAGER_START:
          break;
        case UNIMOUSE_MANAGER_LOCKSTEP_ON:
          if (s[kLockstep] == 0) ctx.Log("lock-step on: the simulation waits for the firmware");
          s[kLockstep] = 1;
          heard.lockstep_on = true;
          ctx.SetFirmwarePaced(true);
          break;
        case UNIMOUSE_MANAGER_STEP_DONE:
          heard.step_done = true;
          break;
        case UNIMOUSE_MANAGER_REPEATS_COMMANDS:
          if (s[kRepeats] == 0 && p_.failsafe_s > 0) {
            std::snprintf(text, sizeof(text),
                          "the firmware repeats its commands: %g s of silence will stop the "
                          "motors",
                          p_.failsafe_s);
            ctx.Log(text);
          }
          s[kRepeats] = 1;
          break;
        case UNIMOUSE_MANAGER_MAZE_INFO:
          s[kMazeAsked] = 1;
          if (!maze_.goal_is_rectangle) {
            ctx.Warn(
                "the firmware asked for the maze: its goal cells are not a rectangle, so "
                "the frame's goal rectangle holds other cells too");
          }
          break;
        case UNIMOUSE_MANAGER_FRAME_SIZES:
          s[kSizesAsked] = 1;
          break;
        default:
          std::snprintf(text, sizeof(text), "unknown manager byte 0x%02x, ignored", f.value);
          ctx.Warn(text);
      }
      break;
    case UNIMOUSE_ID_LOG:
      ctx.Firmware(f.text);
      break;
    case UNIMOUSE_ID_MAZE_SIZE:
      if (f.data[0] != maze_.width_cells || f.data[1] != maze_.height_cells) {
        std::snprintf(text, sizeof(text),
                      "the firmware works with a %d x %d maze, but the world's maze is %d x %d: "
                      "it cannot know the whole maze",
                      f.data[0], f.data[1], maze_.width_cells, maze_.height_cells);
        ctx.Warn(text);
      }
      break;
    case UNIMOUSE_ID_DEBUG_WALLS: {
      beliefs_.walls[{f.data[0], f.data[1]}] = {f.data[2], f.data[3]};
      unimouse_report r{};
      r.size = sizeof(r);
      r.kind = UNIMOUSE_REPORT_WALLS;
      r.x = f.data[0];
      r.y = f.data[1];
      r.walls = f.data[2];
      r.known = f.data[3];
      ctx.Report(r);
      std::snprintf(text, sizeof(text), "debug walls (%d, %d): %s; known %s", f.data[0], f.data[1],
                    Sides(f.data[2]).c_str(), Sides(f.data[3]).c_str());
      ctx.Detail(text);
      break;
    }
    case UNIMOUSE_ID_DEBUG_VISITED: {
      if (beliefs_.visited.size() < kMaxVisitedKept)
        beliefs_.visited.emplace_back(f.data[0], f.data[1]);
      unimouse_report r{};
      r.size = sizeof(r);
      r.kind = UNIMOUSE_REPORT_VISITED;
      r.x = f.data[0];
      r.y = f.data[1];
      ctx.Report(r);
      std::snprintf(text, sizeof(text), "debug visited (%d, %d)", f.data[0], f.data[1]);
      ctx.Detail(text);
      break;
    }
    case UNIMOUSE_ID_DEBUG_PATH: {
      beliefs_.path.clear();
      std::vector<int> cells;
      for (size_t i = 0; i + 1 < f.data.size(); i += 2) {
        beliefs_.path.emplace_back(f.data[i], f.data[i + 1]);
        cells.push_back(f.data[i]);
        cells.push_back(f.data[i + 1]);
      }
      unimouse_report r{};
      r.size = sizeof(r);
      r.kind = UNIMOUSE_REPORT_PATH;
      r.cells = cells.data();
      r.ncells = static_cast<int>(cells.size() / 2);
      ctx.Report(r);
      std::string path = "debug path";
      for (size_t i = 0; i + 1 < f.data.size(); i += 2) {
        path += " (" + std::to_string(f.data[i]) + ", " + std::to_string(f.data[i + 1]) + ")";
      }
      ctx.Detail(path);
      break;
    }
    case UNIMOUSE_ID_DEBUG_VALUE: {
      unimouse_report r{};
      r.size = sizeof(r);
      r.kind = UNIMOUSE_REPORT_VALUE;
      r.name = f.text.c_str();
      r.value = f.number;
      ctx.Report(r);
      std::snprintf(text, sizeof(text), "debug value %s = %.9g", f.text.c_str(), f.number);
      ctx.Detail(text);
      break;
    }
  }
}

bool Link::Commanded(const SenseContext& ctx) const {
  for (const Incoming& i : receive_) {
    if (ctx.Read(i.signal) != 0) return true;
  }
  return false;
}

bool Link::FailIfFirmwareFailed(const SenseContext& ctx) const {
  const std::string failure = transport_->Failure();
  if (!failure.empty()) ctx.Fail(failure + " at t=" + Seconds(ctx.time_s()) + " s");
  return !failure.empty();
}

void Link::ApplyInOrder(const SenseContext& ctx, const std::vector<uint8_t>& bytes,
                        Heard& heard) const {
  // in the order it happened: a peer that came since the last look (in this read, or in a
  // write's reconnection) came before its bytes, and one that went went after them, even one
  // that came and went within one read (a client that connects, sends and closes inside a step)
  const bool came = transport_->peers() != peers_seen_;
  peers_seen_ = transport_->peers();
  if (came || (transport_->Connected() && !was_connected_)) {
    if (was_connected_) PeerLost(ctx, heard);
    PeerCame(ctx);
  }
  std::vector<FirmwareFrame> frames;
  decoder_.Feed(bytes, frames);
  for (const FirmwareFrame& f : frames) Apply(ctx, f, heard);
  if (was_connected_ && !transport_->Connected()) PeerLost(ctx, heard);
}

void Link::PeerCame(const SenseContext& ctx) const {
  was_connected_ = true;
  ctx.Log("firmware connected");
  if (frames_ever_ > 0) {
    ++reconnections_;
    WithinRestarts(ctx, reconnections_, "the firmware's link came back");
  }
}

void Link::PeerLost(const SenseContext& ctx, Heard& heard) const {
  was_connected_ = false;
  // a lost link always stops the motors, whatever the firmware said
  const bool commanded = Commanded(ctx);
  FirmwareStartsOver(ctx);
  ctx.Log(commanded ? "firmware disconnected: motors stopped" : "firmware disconnected");
  // a firmware that crashed or quit is the run's error, not a cable pulled out
  FailIfFirmwareFailed(ctx);
  decoder_.Reset();
  // what the next firmware says of itself is its own, and lock-step waits for a firmware
  // that is there: it comes back when the next one asks
  ctx.state()[kRepeats] = 0;
  ctx.SetFirmwarePaced(false);
  heard.gone_or_restarted = true;
}

void Link::FirmwareStartsOver(const SenseContext& ctx) const {
  ZeroReceived(ctx);
  ctx.state()[kLockstep] = 0;
  startup_codes_in_a_row_ = 0;
  if (frames_ever_ > 0) next_frame_restarts_ = true;
}

void Link::Receive(const SenseContext& ctx, Heard& heard) const {
  inbox_.clear();
  // a firmware that floods cannot keep the step reading forever
  if (read_this_step_ < kReadPerStep_bytes) {
    transport_->Read(inbox_, kReadPerStep_bytes - read_this_step_);
  }
  read_this_step_ += inbox_.size();
  received_bytes_ += inbox_.size();
  TakeText(ctx);
  ApplyInOrder(ctx, inbox_, heard);
  if (decoder_.text_lines() > 0 && !text_said_) {
    text_said_ = true;
    ctx.Log(
        "the firmware writes plain text between its frames (Serial.print on a board): each "
        "line is logged as a line of its log");
  }

  // each unknown id is reported once; all are counted
  std::span<double> s = ctx.state();
  const auto& unknown = decoder_.unknown_ids();
  for (size_t i = static_cast<size_t>(s[kUnknownReported]); i < unknown.size(); ++i) {
    char text[96];
    std::snprintf(text, sizeof(text), "unknown frame id 0x%02x from the firmware: skipped",
                  unknown[i]);
    ctx.Warn(text);
  }
  s[kUnknownReported] = static_cast<double>(unknown.size());
}

void Link::TakeText(const SenseContext& ctx) const {
  // what a PC-built firmware printed (printf, std::cout) is its log, as its log frames are
  text_.clear();
  transport_->TakeText(text_);
  for (const std::string& line : text_) ctx.Firmware(line);
}

void Link::Send(const SenseContext& ctx, const std::string& frames, bool lockstep) const {
  // in lock-step the firmware waits for every byte: no line to emulate, nothing to drop
  if (lockstep || bytes_per_step_ <= 0) {
    queue_ += frames;
    const size_t n = transport_->Write(
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(queue_.data()), queue_.size()));
    queue_.erase(0, n);
    if (queue_.size() > static_cast<size_t>(p_.queue_bytes)) queue_.clear();
    return;
  }
  // whole frames join the queue while there is room; the line drains it at its baud rate
  if (queue_.size() + frames.size() <= static_cast<size_t>(p_.queue_bytes)) {
    queue_ += frames;
  } else {
    if (dropped_bytes_ == 0) {
      ctx.Warn(
          "the line is slower than the frames: frames dropped (raise the baud rate, or "
          "turn sensors off while idle)");
    }
    dropped_bytes_ += frames.size();
  }
  budget_bytes_ = std::min(budget_bytes_ + bytes_per_step_, bytes_per_step_ + 16);
  const size_t can = std::min(queue_.size(), static_cast<size_t>(budget_bytes_));
  if (can == 0) return;
  const size_t n = transport_->Write(
      std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(queue_.data()), can));
  queue_.erase(0, n);
  budget_bytes_ -= static_cast<double>(n);
}

bool Link::AwaitFirmware(const SenseContext& ctx, Heard& heard, bool Heard::*until,
                         const char* waiting_for) const {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(p_.lockstep_timeout_s);
  char text[192];
  while (!(heard.*until)) {
    // a firmware that went away or started over owes this step nothing
    if (heard.gone_or_restarted) return true;
    if (read_this_step_ >= kReadPerStep_bytes) {
      std::snprintf(text, sizeof(text),
                    "the firmware sent more than %zu bytes at t=%.3f s and did not %s (lock-step)",
                    kReadPerStep_bytes, ctx.time_s(), waiting_for);
      ctx.Fail(text);
      return false;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !transport_->WaitReadable(left)) {
      // a peer that closed its side is a lost link, not a hang: a read tells which
      Receive(ctx, heard);
      if (heard.gone_or_restarted || heard.*until) continue;
      // the last lines a firmware printed before it hung or crashed are the ones that matter
      TakeText(ctx);
      if (FailIfFirmwareFailed(ctx)) return false;
      std::snprintf(text, sizeof(text),
                    "the firmware did not %s at t=%.3f s within %g s (lock-step)", waiting_for,
                    ctx.time_s(), p_.lockstep_timeout_s);
      ctx.Fail(text);
      return false;
    }
    Receive(ctx, heard);
  }
  return true;
}

bool Link::AwaitStartUp(const SenseContext& ctx, Heard& heard) const {
  const std::vector<uint8_t> codes = {UNIMOUSE_ID_MANAGER, kStartupCodes[0],    UNIMOUSE_ID_MANAGER,
                                      kStartupCodes[1],    UNIMOUSE_ID_MANAGER, kStartupCodes[2]};
  const auto opened = std::chrono::steady_clock::now();
  const auto deadline = opened + std::chrono::duration<double>(p_.wait_for_firmware_s);
  std::vector<uint8_t> pending;
  for (;;) {
    const size_t before = pending.size();
    transport_->Read(pending, kReadPerStep_bytes);
    received_bytes_ += pending.size() - before;
    const auto at = std::search(pending.begin(), pending.end(), codes.begin(), codes.end());
    if (at != pending.end()) {
      skipped_before_start_up_ += static_cast<uint64_t>(at - pending.begin());
      pending.erase(pending.begin(), at);
      break;
    }
    // all but a start of the codes is skipped
    const size_t keep = std::min(pending.size(), codes.size() - 1);
    skipped_before_start_up_ += pending.size() - keep;
    pending.erase(pending.begin(), pending.end() - static_cast<long>(keep));
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      char text[224];
      std::snprintf(text, sizeof(text),
                    "no start-up frames from the firmware within %g s (wait_for_firmware_s); %llu "
                    "bytes came before",
                    p_.wait_for_firmware_s,
                    static_cast<unsigned long long>(skipped_before_start_up_ + pending.size()));
      ctx.Fail(text);
      return false;
    }
    // a port that is not there yet cannot be waited on: look again shortly
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now);
    if (!transport_->WaitReadable(std::min(left, std::chrono::milliseconds(100)))) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  char text[224];
  std::snprintf(text, sizeof(text),
                "the firmware's start-up frames came %.3f s after the link opened; %llu bytes "
                "before them skipped (a bootloader's, or a reset's noise)",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - opened).count(),
                static_cast<unsigned long long>(skipped_before_start_up_));
  ctx.Log(text);
  ApplyInOrder(ctx, pending, heard);
  return true;
}

void Link::RunBoard(const SenseContext& ctx, Heard& heard, bool lockstep) const {
  ctx.SetFirmwarePaced(true);
  const std::string fault = transport_->RunUntil(ctx.time_s() + period_s_);
  if (!fault.empty()) {
    ctx.Fail(fault);
    return;
  }
  for (const std::string& cause : transport_->TakeResets()) {
    // the board boots again; the firmware's start-up frames say when it is back
    ++board_resets_;
    FirmwareStartsOver(ctx);
    lockstep = false;
    ctx.Log("the emulated board was reset by " + cause + " before t=" +
            Seconds(ctx.time_s() + period_s_) + " s: the firmware boots again, motors stopped");
    if (!WithinRestarts(ctx, board_resets_, "the emulated board was reset")) return;
  }
  for (const std::string& notice : transport_->TakeNotices()) ctx.Warn(notice);
  Receive(ctx, heard);
  if (!lockstep) return;
  // a step not finished within its cycles is late, as on a real board; its commands count when
  // they come
  if (heard.step_done) {
    last_step_done_s_ = ctx.time_s();
    return;
  }
  ++late_steps_;
  if (ctx.time_s() - last_step_done_s_ > p_.lockstep_timeout_s) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "the firmware did not finish a step for %g s of its own time at t=%.3f s "
                  "(lock-step)",
                  p_.lockstep_timeout_s, ctx.time_s());
    ctx.Fail(text);
  }
}

void Link::Sense(const SenseContext& ctx) const {
  // a link that was only checked, never started, has nothing to talk to
  if (transport_ == nullptr) return;
  std::span<double> s = ctx.state();
  read_this_step_ = 0;
  Heard heard;
  if (p_.wait_for_firmware_s > 0 && ctx.step() == 0 && !AwaitStartUp(ctx, heard)) return;
  Receive(ctx, heard);
  if (static_cast<double>(received_bytes_) >
      kFloodAllowance_bytes + kFloodRate_bytes_per_s * ctx.time_s()) {
    char text[192];
    std::snprintf(text, sizeof(text),
                  "the firmware floods the link: %llu bytes by t=%.3f s, more than 1 MiB and "
                  "1 MiB a simulated second",
                  static_cast<unsigned long long>(received_bytes_), ctx.time_s());
    ctx.Fail(text);
    return;
  }
  if (transport_->lockstep_from_start() && p_.extensions && ctx.step() == 0 && s[kLockstep] == 0 &&
      !AwaitFirmware(ctx, heard, &Heard::lockstep_on, "ask for lock-step")) {
    return;
  }

  // failsafe: a silent board stops its motors, if it said that it repeats its commands
  const bool commanded = Commanded(ctx);
  const bool repeats = s[kRepeats] != 0 || s[kLockstep] != 0;
  if (p_.failsafe_s > 0 && repeats && s[kFailsafe] == 0 &&
      ctx.time_s() - s[kLastFrame_s] > p_.failsafe_s && commanded) {
    ZeroReceived(ctx);
    s[kFailsafe] = 1;
    char text[128];
    std::snprintf(text, sizeof(text),
                  "no frame from the firmware for %g s: motors stopped (every received signal "
                  "set to 0)",
                  p_.failsafe_s);
    ctx.Warn(text);
  }

  // the send table, in its order, each entry on the steps of its period
  std::string out;
  if (s[kSensorsOn] != 0) {
    const int64_t step = ctx.step() / physics_steps_per_step_;
    for (const Outgoing& o : send_) {
      if (step % o.every_n_steps == 0) {
        PutDataFrame(o.entry.id, o.entry.encoding, ctx.Read(o.signal), p_.tof_full_scale_m, out);
      }
    }
  }
  if (s[kMazeAsked] != 0) {
    PutMazeInfoFrame(maze_, out);
    s[kMazeAsked] = 0;
  }
  if (s[kSizesAsked] != 0) {
    // the protocol sizes its own sensor frames: only the others need saying
    for (const Outgoing& o : send_) {
      if (unimouse_payload_size(o.entry.id) != EncodingSize(o.entry.encoding)) {
        PutFrameSizeFrame(o.entry.id, o.entry.encoding, out);
      }
    }
    s[kSizesAsked] = 0;
  }
  const bool lockstep = s[kLockstep] != 0;
  if (lockstep) PutClockFrame(static_cast<uint64_t>(std::llround(ctx.time_s() * 1e6)), out);
  Send(ctx, out, lockstep);

  // an emulated board keeps its own time: it runs the step's cycles and is never waited for,
  // its bus's IMU reading what the IMU component reads now
  if (!p_.spi_imu.empty()) {
    double values[6];
    for (int i = 0; i < 6; ++i) values[i] = ctx.Read(imu_[i]);
    transport_->SetImuReading(std::span<const double, 6>(values));
  }
  if (transport_->clocked()) {
    RunBoard(ctx, heard, lockstep);
    return;
  }

  // lock-step: this step is over when the firmware says so
  if (lockstep) AwaitFirmware(ctx, heard, &Heard::step_done, "finish its step");
}

void Link::Finish(const SenseContext& ctx) const {
  if (transport_ == nullptr) return;
  TakeText(ctx);
  if (!beliefs_path_.empty()) {
    std::FILE* f = std::fopen(beliefs_path_.c_str(), "w");
    if (f == nullptr) {
      ctx.Warn(beliefs_path_ + ": cannot write the firmware's beliefs");
    } else {
      auto cells = [&](const std::vector<std::pair<int, int>>& list) {
        for (size_t i = 0; i < list.size(); ++i) {
          std::fprintf(f, "%s[%d, %d]", i ? ", " : "", list[i].first, list[i].second);
        }
      };
      std::fprintf(f, "{\"walls\": [");
      size_t i = 0;
      for (const auto& [cell, wk] : beliefs_.walls) {
        std::fprintf(f, "%s[%d, %d, %d, %d]", i++ ? ", " : "", cell.first, cell.second, wk.first,
                     wk.second);
      }
      std::fprintf(f, "],\n \"visited\": [");
      cells(beliefs_.visited);
      std::fprintf(f, "],\n \"path\": [");
      cells(beliefs_.path);
      std::fprintf(f, "]}\n");
      std::fclose(f);
    }
  }
  char text[160];
  std::snprintf(text, sizeof(text),
                "%llu frames from the firmware, %llu unknown bytes; %llu bytes dropped",
                static_cast<unsigned long long>(decoder_.frames()),
                static_cast<unsigned long long>(decoder_.unknown_bytes()),
                static_cast<unsigned long long>(dropped_bytes_));
  ctx.Log(text);
  const std::string summary = transport_->Summary();
  if (!summary.empty()) {
    std::snprintf(text, sizeof(text), "; %llu lock-step steps late",
                  static_cast<unsigned long long>(late_steps_));
    ctx.Log(summary + text);
  }
  // the same, typed, for the run's record
  auto measured = transport_->Measurements();
  if (!measured.empty()) measured.emplace_back("lockstep_late_steps", late_steps_);
  for (const auto& [name, value] : measured) {
    unimouse_report r{};
    r.size = sizeof(r);
    r.kind = UNIMOUSE_REPORT_MEASURE;
    r.name = name.c_str();
    r.value = value;
    ctx.Report(r);
  }
}

}  // namespace unimouse::link
