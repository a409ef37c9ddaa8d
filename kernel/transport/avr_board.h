// SPDX-License-Identifier: GPL-3.0-or-later
// An emulated Arduino board: the firmware's .elf on an ATmega (simavr, in this process), run in
// lock-step with the simulation. Time is the MCU's own: each call runs the cycles up to a given
// simulated time, and bytes cross UART0 at the baud rate the firmware configured, one every byte
// time of the emulator, with no flow control, so a firmware that reads too slowly loses bytes as
// a real board would. No thread and no wall clock touch the run: the same image gives the same
// run. It also watches what a real board would only show by misbehaving: how deep the stack got
// against the data below it, lost bytes, the latency from sensor frames to motor commands, and a
// crash, a watchdog reset or a sleep with interrupts off, which end its run.
#ifndef UNIMOUSE_TRANSPORT_AVR_BOARD_H_
#define UNIMOUSE_TRANSPORT_AVR_BOARD_H_

#include <cstdarg>
#include <cstdint>
#include <deque>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

struct avr_t;
struct avr_irq_t;

namespace unimouse::link {

/// What an emulated board measured over its run; every figure is in emulated cycles or bytes,
/// so it repeats exactly, except host_cpu_s (the host's own time, for speed only).
struct AvrBoardStats {
  std::string mcu;        ///< part name, "atmega2560"
  uint32_t f_cpu_hz = 0;  ///< MCU clock
  uint64_t cycles = 0;    ///< cycles run, sleeping ones included
  uint64_t instructions = 0;
  uint64_t sleep_cycles = 0;  ///< cycles the MCU spent in SLEEP
  double host_cpu_s = 0;      ///< host CPU time spent emulating
  // RAM: the stack grows down from RAMEND towards the data (.data, .bss, then the heap)
  uint32_t sram_bytes = 0;            ///< the part's SRAM
  uint32_t static_bytes = 0;          ///< .data and .bss
  uint32_t heap_bytes = 0;            ///< heap at the deepest stack (malloc's break over .bss)
  uint32_t stack_max_bytes = 0;       ///< deepest stack, from RAMEND
  uint32_t ram_high_water_bytes = 0;  ///< static + heap + deepest stack
  // UART0, both ways
  uint32_t baud = 0;                ///< rate the firmware configured last
  uint64_t bytes_to_mcu = 0;        ///< bytes that reached the MCU's receiver
  uint64_t bytes_from_mcu = 0;      ///< bytes the MCU sent that reached the host
  uint64_t rx_overruns = 0;         ///< bytes lost with the receiver's FIFO full (DOR)
  uint64_t dropped_to_mcu = 0;      ///< bytes lost on the way in: overruns, and more waiting
                                    ///< than the line could ever carry
  uint64_t before_receiver_on = 0;  ///< bytes sent before the firmware enabled its receiver
  uint64_t dropped_from_mcu = 0;    ///< bytes written to a full transmitter, or never read
  // latency from the last byte of a step's frames to the end of the next motor command
  std::vector<uint32_t> latency_cycles;

  /// Returns emulated seconds.
  double emulated_s() const { return f_cpu_hz ? static_cast<double>(cycles) / f_cpu_hz : 0; }
  /// Returns emulated cycles per host CPU second, in MHz.
  double emulated_mhz() const {
    return host_cpu_s > 0 ? static_cast<double>(cycles) / host_cpu_s / 1e6 : 0;
  }
  /// Returns the latency at quantile q (0..1) in seconds, or -1 without samples.
  double LatencyQuantile_s(double q) const;
  /// Returns one line for a log: speed, RAM, UART and latency.
  std::string Describe() const;
  /// Returns every figure as a named number, the unit in its name ("ram_high_water_bytes").
  std::vector<std::pair<std::string, double>> Named() const;
};

class AvrBoard {
 public:
  struct Options {
    std::string mcu = "atmega2560";             ///< used unless the image names its part (AVR_MCU)
    uint32_t f_cpu_hz = 16000000;               ///< used unless the image names its clock
    size_t queue_bytes = 1024;                  ///< bytes waiting for the line into the MCU at most
    std::vector<uint8_t> command_ids = {5, 6};  ///< frames whose arrival ends a latency sample
    bool resets_restart = true;  ///< a watchdog reset boots the firmware again; false: a fault
  };
  /// What resets the MCU from outside, as MCUSR tells the firmware.
  enum class ResetCause { kExternal, kBrownOut };

  /// Loads `elf_path` onto a fresh MCU, held at reset until the first RunUntil. Throws
  /// InputError when the file fails the image check (avr_image.h), names a part simavr does not
  /// know, or does not fit the part's memories.
  AvrBoard(const std::string& elf_path, const Options& options);
  AvrBoard(const AvrBoard&) = delete;
  AvrBoard& operator=(const AvrBoard&) = delete;
  ~AvrBoard();

  /// Runs the MCU until cycle `cycle` (it may overshoot by one instruction) and returns ""; or,
  /// when the firmware cannot go on (crash, watchdog reset, sleep with interrupts off, stack into
  /// the data), returns why, with the program counter and function, and stays stopped.
  std::string RunUntil(uint64_t cycle);
  /// Runs until simulated time `time_s`, counted from the board's reset.
  std::string RunUntilTime(double time_s);
  /// Resets the MCU now, as its reset pin or a brown-out does: the firmware boots again (or,
  /// without resets_restart, the board stops with that as its fault).
  void Reset(ResetCause cause);
  /// Returns what reset the MCU since the last call, oldest first ("the watchdog").
  std::vector<std::string> TakeResets();
  /// Returns, once each, what a user should know since the last call: that bytes for the MCU
  /// are being lost, and why.
  std::vector<std::string> TakeNotices() { return std::exchange(notices_, {}); }
  /// Queues bytes for the MCU's receiver; they go at the line's pace once it is enabled. Bytes
  /// sent before are lost (counted), as are writes that would overfill the queue.
  void Write(std::span<const uint8_t> bytes);
  /// Appends up to `max_bytes` of the bytes the MCU sent that have arrived by now.
  void Read(std::vector<uint8_t>& out, size_t max_bytes = SIZE_MAX);
  /// Whether the firmware has enabled its receiver (Serial.begin).
  bool receiver_on() const { return receiver_on_; }
  /// Why the firmware stopped, or "".
  const std::string& fault() const { return fault_; }
  uint64_t cycle() const;
  /// Returns the program counter, a byte address.
  uint32_t pc() const;
  /// Returns MCUSR, where the firmware reads why the MCU last reset (EXTRF 0x02, BORF 0x04,
  /// WDRF 0x08).
  uint8_t reset_flags() const;
  /// Returns the measurements so far.
  AvrBoardStats stats() const;
  /// Returns the function that holds byte address `pc`, or "" when no symbol does.
  std::string FunctionAt(uint32_t pc) const;
  /// Returns the address of a data symbol (without the 0x800000 offset), or -1.
  int64_t DataSymbol(const std::string& name) const;
  /// Returns the emulated MCU, for peripherals wired to its pins and buses (spi_imu.h).
  avr_t* mcu() const { return avr_; }

 private:
  static void OnOutput(avr_irq_t* irq, uint32_t value, void* param);
  static void OnXon(avr_irq_t* irq, uint32_t value, void* param);
  static void OnXoff(avr_irq_t* irq, uint32_t value, void* param);
  static uint64_t FeedByte(avr_t* avr, uint64_t when, void* param);
  static uint64_t StepEnd(avr_t* avr, uint64_t when, void* param);
  static void Logger(avr_t* avr, int level, const char* format, va_list ap);
  // keeps `text` for TakeNotices unless `told` says it was kept before
  void NoteOnce(bool& told, std::string text) {
    if (!told) notices_.push_back(std::move(text));
    told = true;
  }
  // frees the MCU and forgets it
  void Release();
  // cycles one 8N1 byte takes on the line as the firmware configured it (simavr's word size)
  uint32_t CyclesPerByte() const;
  uint32_t CyclesPerBit() const;
  uint32_t Baud() const;
  void StartLine();
  void NoteSp();
  void Stop(const std::string& why);
  // what a reset leaves behind: an idle line in, a receiver off, the step's end timer again
  void AfterReset(const std::string& cause);
  // follows the MCU's frames to time the motor commands
  void WalkOutgoing(uint8_t byte, uint64_t arrival);

  avr_t* avr_ = nullptr;
  void (*run_)(avr_t*) = nullptr;  // simavr's own run step; replaced while a watchdog resets
  Options options_;
  AvrBoardStats stats_;
  std::string fault_;
  std::string last_error_;  // simavr's last complaint, for a crash's message
  // symbols of the image: functions by address, data by name
  struct Function {
    uint32_t size;
    std::string name;
  };
  std::map<uint32_t, Function> functions_;
  std::map<std::string, uint32_t> data_symbols_;
  uint32_t ram_start_ = 0, ram_end_ = 0, data_top_ = 0;
  int64_t brkval_ = -1;  // address of malloc's break, when the image has one
  uint16_t min_sp_ = 0xFFFF;
  // into the MCU: bytes waiting for the line, and which of them end a write
  avr_irq_t* uart_in_ = nullptr;
  uint64_t target_ = 0;               // the cycle the current RunUntil runs to
  std::vector<std::string> resets_;   // not yet taken
  std::vector<std::string> notices_;  // not yet taken
  bool told_line_full_ = false;
  bool told_overrun_ = false;
  std::deque<uint8_t> to_mcu_;
  std::deque<bool> ends_write_;
  bool line_busy_ = false;
  bool receiver_on_ = false;
  bool fifo_full_ = false;
  // out of the MCU: bytes with the cycle their stop bit ends
  std::deque<std::pair<uint8_t, uint64_t>> from_mcu_;
  uint64_t tx_free_at_ = 0;
  // latency: when the last byte of a write reached the MCU, waiting for a command
  uint64_t mark_cycle_ = 0;
  bool mark_pending_ = false;
  enum class Walk { kId, kFixed, kText, kPathCount };
  Walk walk_ = Walk::kId;
  int walk_need_ = 0;  // payload bytes still to come
  bool walk_text_after_ = false;
  bool walk_command_ = false;
};

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_AVR_BOARD_H_
