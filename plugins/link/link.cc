// SPDX-License-Identifier: GPL-3.0-or-later
#include "link.h"

#include <chrono>
#include <cmath>
#include <cstdio>

namespace unimouse::link {
namespace {

// state slots: what the firmware asked for, and when it last spoke
constexpr int kSensorsOn = 0;
constexpr int kLockstep = 1;
constexpr int kLastFrame_s = 2;
constexpr int kFailsafe = 3;
constexpr int kUnknownReported = 4;

std::string Sides(uint8_t bits) {
  std::string out;
  const char* names[] = {"N", "E", "S", "W"};
  for (int i = 0; i < 4; ++i) {
    if (bits >> i & 1) out += (out.empty() ? "" : " ") + std::string(names[i]);
  }
  return out.empty() ? "none" : out;
}

std::unique_ptr<Transport> Open(const LinkParams& p) {
  if (p.transport.rfind("avr:", 0) == 0) {
#ifdef UNIMOUSE_HAVE_SIMAVR
    return OpenAvrBoard(p.transport.substr(4), p.mcu, p.f_cpu_hz);
#else
    throw InputError("avr: this build has no emulated board (it needs libsimavr-dev, libelf-dev)");
#endif
  }
  return OpenTransport(p.transport);
}

}  // namespace

Link::Link(Params params) : p_(std::move(params)), transport_(Open(p_)) {}

Link::~Link() = default;

void Link::Bind(BindContext& ctx) {
  tof_[0] = ctx.ReadSignal(p_.tof_left);
  tof_[1] = ctx.ReadSignal(p_.tof_right);
  tof_[2] = ctx.ReadSignal(p_.tof_front);
  encoder_[0] = ctx.ReadSignal(p_.encoder_left);
  encoder_[1] = ctx.ReadSignal(p_.encoder_right);
  motor_[0] = ctx.WriteSignal(p_.motor_left);
  motor_[1] = ctx.WriteSignal(p_.motor_right);
  lockstep_ = ctx.WriteSignal(p_.lockstep_out);
  const double steps = p_.tof_period_s / ctx.period_s();
  tof_every_n_steps_ = std::max(1, static_cast<int>(std::lround(steps)));
  period_s_ = ctx.period_s();
  UNIMOUSE_THROW_UNLESS(std::fabs(steps - tof_every_n_steps_) < 1e-6 * steps,
                        "tof_period_s must be a whole number of the link's steps");
  ctx.SetStateSize(5);
  // a serial port's own rate limits it; pty and TCP go as fast as they are read unless told
  int baud = p_.baud;
  const size_t at = p_.transport.rfind('@');
  if (baud == 0 && p_.transport.rfind("serial:", 0) == 0 && at != std::string::npos) {
    baud = std::stoi(p_.transport.substr(at + 1));
  }
  bytes_per_step_ = baud > 0 ? baud / 10.0 * ctx.period_s() : 0;
  if (!p_.beliefs_out.empty()) beliefs_path_ = ctx.output_dir() + "/" + p_.beliefs_out;
}

void Link::Reset(const ResetContext& ctx) const {
  std::span<double> s = ctx.state();
  s[kSensorsOn] = 1;  // the original streamed from the start
  s[kLockstep] = 0;
  s[kLastFrame_s] = 0;
  s[kFailsafe] = 0;
  s[kUnknownReported] = 0;
  ctx.Write(motor_[0], 0);
  ctx.Write(motor_[1], 0);
  ctx.Write(lockstep_, 0);
  decoder_.Reset();
  late_steps_ = 0;
  last_step_done_s_ = 0;
  ctx.Log("firmware link: " + transport_->Describe());
}

void Link::Apply(const SenseContext& ctx, const FirmwareFrame& f, bool* step_done) const {
  std::span<double> s = ctx.state();
  s[kLastFrame_s] = ctx.time_s();
  if (s[kFailsafe] != 0) {
    s[kFailsafe] = 0;
    ctx.Log("the firmware speaks again");
  }
  char text[160];
  switch (f.id) {
    case UNIMOUSE_ID_MOTOR_LEFT:
    case UNIMOUSE_ID_MOTOR_RIGHT:
      ctx.Write(motor_[f.id - UNIMOUSE_ID_MOTOR_LEFT], f.value);
      break;
    case UNIMOUSE_ID_MANAGER:
      switch (f.value) {
        case UNIMOUSE_MANAGER_SENSORS_ON:
        case UNIMOUSE_MANAGER_SENSORS_OFF:
          s[kSensorsOn] = f.value == UNIMOUSE_MANAGER_SENSORS_ON;
          break;
        case UNIMOUSE_MANAGER_STOP:
          ctx.Write(motor_[0], 0);
          ctx.Write(motor_[1], 0);
          break;
        case UNIMOUSE_MANAGER_START:
          break;
        case UNIMOUSE_MANAGER_LOCKSTEP_ON:
          if (s[kLockstep] == 0) ctx.Log("lock-step on: the simulation waits for the firmware");
          s[kLockstep] = 1;
          ctx.Write(lockstep_, 1);
          ctx.SetFirmwarePaced(true);
          break;
        case UNIMOUSE_MANAGER_STEP_DONE:
          *step_done = true;
          break;
        default:
          std::snprintf(text, sizeof(text), "unknown manager byte 0x%02x, ignored", f.value);
          ctx.Warn(text);
      }
      break;
    case UNIMOUSE_ID_LOG:
      ctx.Firmware(f.text);
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
      ctx.Log(text);
      break;
    }
    case UNIMOUSE_ID_DEBUG_VISITED: {
      beliefs_.visited.emplace_back(f.data[0], f.data[1]);
      unimouse_report r{};
      r.size = sizeof(r);
      r.kind = UNIMOUSE_REPORT_VISITED;
      r.x = f.data[0];
      r.y = f.data[1];
      ctx.Report(r);
      std::snprintf(text, sizeof(text), "debug visited (%d, %d)", f.data[0], f.data[1]);
      ctx.Log(text);
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
      ctx.Log(path);
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
      ctx.Log(text);
      break;
    }
  }
}

void Link::Receive(const SenseContext& ctx, bool* step_done) const {
  inbox_.clear();
  transport_->Read(inbox_);
  if (transport_->Connected() != was_connected_) {
    was_connected_ = transport_->Connected();
    ctx.Log(was_connected_ ? "firmware connected" : "firmware disconnected");
    if (!was_connected_) decoder_.Reset();
  }
  std::vector<FirmwareFrame> frames;
  decoder_.Feed(inbox_, frames);
  for (const FirmwareFrame& f : frames) Apply(ctx, f, step_done);

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

bool Link::AwaitFirmware(const SenseContext& ctx, bool* step_done, const char* waiting_for) const {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(p_.lockstep_timeout_s);
  const bool for_lockstep = step_done == nullptr;
  bool ignored = false;
  while (for_lockstep ? ctx.state()[kLockstep] == 0 : !*step_done) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !transport_->WaitReadable(left)) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    "the firmware did not %s at t=%.3f s within %g s (lock-step)", waiting_for,
                    ctx.time_s(), p_.lockstep_timeout_s);
      ctx.Fail(text);
      return false;
    }
    Receive(ctx, for_lockstep ? &ignored : step_done);
  }
  return true;
}

void Link::Sense(const SenseContext& ctx) const {
  std::span<double> s = ctx.state();
  bool step_done = false;
  Receive(ctx, &step_done);
  if (p_.start_with_lockstep && ctx.step() == 0 && s[kLockstep] == 0 &&
      !AwaitFirmware(ctx, nullptr, "ask for lock-step")) {
    return;
  }

  // failsafe: a silent board stops its motors
  if (p_.failsafe_s > 0 && s[kFailsafe] == 0 && ctx.time_s() - s[kLastFrame_s] > p_.failsafe_s &&
      (ctx.Read(motor_[0]) != 0 || ctx.Read(motor_[1]) != 0)) {
    ctx.Write(motor_[0], 0);
    ctx.Write(motor_[1], 0);
    s[kFailsafe] = 1;
    char text[96];
    std::snprintf(text, sizeof(text), "no frame from the firmware for %g s: motors stopped",
                  p_.failsafe_s);
    ctx.Warn(text);
  }

  std::string out;
  if (s[kSensorsOn] != 0) {
    PutEncoderFrame(UNIMOUSE_ID_ENCODER_LEFT, std::lround(ctx.Read(encoder_[0])), out);
    PutEncoderFrame(UNIMOUSE_ID_ENCODER_RIGHT, std::lround(ctx.Read(encoder_[1])), out);
    if (ctx.step() % tof_every_n_steps_ == 0) {
      for (int i = 0; i < 3; ++i) {
        PutTofFrame(static_cast<uint8_t>(UNIMOUSE_ID_TOF_LEFT + i), ctx.Read(tof_[i]),
                    p_.tof_full_scale_m, out);
      }
    }
  }
  const bool lockstep = s[kLockstep] != 0;
  if (lockstep) PutClockFrame(static_cast<uint64_t>(std::llround(ctx.time_s() * 1e6)), out);
  Send(ctx, out, lockstep);

  // an emulated board keeps its own time: it runs the step's cycles, never waits
  if (transport_->clocked()) {
    ctx.SetFirmwarePaced(true);
    const std::string fault = transport_->RunUntil(ctx.time_s() + period_s_);
    if (!fault.empty()) {
      ctx.Fail(fault);
      return;
    }
    Receive(ctx, &step_done);
    if (!lockstep) return;
    if (step_done) {
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
    return;
  }

  // lock-step: this step is over when the firmware says so
  if (!lockstep) return;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(p_.lockstep_timeout_s);
  while (!step_done) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !transport_->WaitReadable(left)) {
      char text[160];
      std::snprintf(text, sizeof(text),
                    "the firmware did not finish its step at t=%.3f s within %g s (lock-step)",
                    ctx.time_s(), p_.lockstep_timeout_s);
      ctx.Fail(text);
      return;
    }
    Receive(ctx, &step_done);
  }
}

void Link::Finish(const SenseContext& ctx) const {
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
                "link: %llu frames from the firmware, %llu unknown bytes; %llu bytes dropped",
                static_cast<unsigned long long>(decoder_.frames()),
                static_cast<unsigned long long>(decoder_.unknown_bytes()),
                static_cast<unsigned long long>(dropped_bytes_));
  ctx.Log(text);
  const std::string summary = transport_->Summary();
  if (!summary.empty()) {
    std::snprintf(text, sizeof(text), "; %llu lock-step steps late",
                  static_cast<unsigned long long>(late_steps_));
    ctx.Log("link: " + summary + text);
  }
}

}  // namespace unimouse::link
