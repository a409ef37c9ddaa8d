// SPDX-License-Identifier: GPL-3.0-or-later
#include "avr_board.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <new>

#include "avr_image.h"
#include "unimouse/errors.h"
#include "unimouse_protocol.h"

extern "C" {
#include "avr_uart.h"
#include "sim_avr.h"
#include "sim_cycle_timers.h"
#include "sim_elf.h"
#include "sim_io.h"
#include "sim_irq.h"
}

namespace unimouse::link {
namespace {

// UART0's registers, at the same data addresses on the ATmega328P and ATmega2560
constexpr uint16_t kUcsr0a = 0xC0, kUcsr0b = 0xC1, kUcsr0c = 0xC2, kUbrr0l = 0xC4, kUbrr0h = 0xC5;
constexpr uint32_t kDataOffset = 0x800000;  // where avr-ld puts the data space
// MCUSR, where the firmware reads why it was reset, and its flags (the same on both parts)
constexpr uint16_t kMcusr = 0x54;
constexpr uint8_t kExtrf = 0x02, kBorf = 0x04;

// the logger is global in simavr: each board registers its MCU here to get its own messages
std::vector<std::pair<avr_t*, AvrBoard*>>& Boards() {
  static std::vector<std::pair<avr_t*, AvrBoard*>> boards;
  return boards;
}

double ThreadCpu_s() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// simavr 1.6 reports a write beyond RAMEND as a crash and then makes it all the same, and reads
// (and, by SPM, writes) the flash at whatever address a jump, a return or Z names: the data
// space gets all the 64 KiB a 16-bit address reaches and the flash the 32 MiB a 24-bit word
// address reaches, so that a firmware that goes astray stops with its crash instead of writing
// over the simulator's memory. The pages beyond the part's own stay untouched, so unallocated.
void WidenMemories(avr_t* avr) {
  constexpr size_t kDataSpace_bytes = size_t{1} << 16;
  // and the two words of the longest instruction read at the last address
  constexpr size_t kFlashSpace_bytes = (size_t{1} << 25) + 4;
  auto* data = static_cast<uint8_t*>(std::calloc(kDataSpace_bytes, 1));
  auto* flash = static_cast<uint8_t*>(std::calloc(kFlashSpace_bytes, 1));
  if (data == nullptr || flash == nullptr) {
    std::free(data);
    std::free(flash);
    throw std::bad_alloc();
  }
  std::memcpy(data, avr->data, avr->ramend + 1u);
  // avr_init puts an opcode that stops the core just past the flash's end
  std::memcpy(flash, avr->flash, avr->flashend + 3u);
  std::free(avr->data);
  std::free(avr->flash);
  avr->data = data;
  avr->flash = flash;
}

// avr_terminate frees the peripherals but not the MCU that avr_make_mcu_by_name allocated, the
// lines of its I/O registers, the interrupt lines that live inside it (their names and hooks) or
// the table of all lines
void FreeMcu(avr_t* avr) {
  avr_terminate(avr);
  for (auto& reg : avr->io) {
    // avr_iomem_getirq allocates 9 lines a register: one a bit and one for the byte
    avr_free_irq(reg.irq, 9);
    reg.irq = nullptr;
  }
  avr_irq_pool_t& pool = avr->irq_pool;
  for (int i = 0; i < pool.count; ++i) {
    // what is left are lines inside the MCU: allocated ones went with their owners
    if (pool.irq[i] != nullptr && !(pool.irq[i]->flags & IRQ_FLAG_ALLOC)) {
      avr_free_irq(pool.irq[i], 1);
    }
  }
  std::free(pool.irq);
  std::free(avr);
}

}  // namespace

double AvrBoardStats::LatencyQuantile_s(double q) const {
  if (latency_cycles.empty() || f_cpu_hz == 0) return -1;
  std::vector<uint32_t> sorted = latency_cycles;
  const size_t last = sorted.size() - 1;
  const size_t k = std::min(last, static_cast<size_t>(q * static_cast<double>(last) + 0.5));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
  return static_cast<double>(sorted[k]) / f_cpu_hz;
}

std::string AvrBoardStats::Describe() const {
  char text[640];
  const double s = emulated_s();
  std::snprintf(
      text, sizeof(text),
      "%s at %.0f MHz: %.3f s emulated, %llu instructions (%.2f MIPS emulated, %.0f %% asleep), "
      "%.1f MHz on this host; RAM high-water %u of %u bytes (data %u, heap %u, stack %u); UART "
      "%u baud: %llu bytes in, %llu out, %llu RX overruns, %llu lost in, %llu lost out, %llu "
      "before the receiver was on; sensor-to-command latency p50 %.3f ms, p99 %.3f ms (%zu)",
      mcu.c_str(), f_cpu_hz / 1e6, s, static_cast<unsigned long long>(instructions),
      s > 0 ? static_cast<double>(instructions) / s / 1e6 : 0.0,
      cycles ? 100.0 * static_cast<double>(sleep_cycles) / static_cast<double>(cycles) : 0.0,
      emulated_mhz(), ram_high_water_bytes, sram_bytes, static_bytes, heap_bytes, stack_max_bytes,
      baud, static_cast<unsigned long long>(bytes_to_mcu),
      static_cast<unsigned long long>(bytes_from_mcu), static_cast<unsigned long long>(rx_overruns),
      static_cast<unsigned long long>(dropped_to_mcu),
      static_cast<unsigned long long>(dropped_from_mcu),
      static_cast<unsigned long long>(before_receiver_on), LatencyQuantile_s(0.5) * 1e3,
      LatencyQuantile_s(0.99) * 1e3, latency_cycles.size());
  return text;
}

std::vector<std::pair<std::string, double>> AvrBoardStats::Named() const {
  const double s = emulated_s();
  auto D = [](auto v) { return static_cast<double>(v); };
  return {
      {"avr.f_cpu_hz", D(f_cpu_hz)},
      {"avr.emulated_s", s},
      {"avr.cycles", D(cycles)},
      {"avr.instructions", D(instructions)},
      {"avr.instructions_per_s", s > 0 ? static_cast<double>(instructions) / s : 0},
      {"avr.asleep_fraction", cycles ? D(sleep_cycles) / D(cycles) : 0},
      {"avr.host_emulated_mhz", D(emulated_mhz())},
      {"avr.host_cpu_s", D(host_cpu_s)},
      {"avr.sram_bytes", D(sram_bytes)},
      {"avr.ram_high_water_bytes", D(ram_high_water_bytes)},
      {"avr.static_bytes", D(static_bytes)},
      {"avr.heap_bytes", D(heap_bytes)},
      {"avr.stack_max_bytes", D(stack_max_bytes)},
      {"avr.uart_baud", D(baud)},
      {"avr.bytes_to_mcu", D(bytes_to_mcu)},
      {"avr.bytes_from_mcu", D(bytes_from_mcu)},
      {"avr.rx_overruns", D(rx_overruns)},
      {"avr.dropped_to_mcu_bytes", D(dropped_to_mcu)},
      {"avr.dropped_from_mcu_bytes", D(dropped_from_mcu)},
      {"avr.before_receiver_on_bytes", D(before_receiver_on)},
      {"avr.latency_p50_s", D(LatencyQuantile_s(0.5))},
      {"avr.latency_p99_s", D(LatencyQuantile_s(0.99))},
      {"avr.latency_samples", D(latency_cycles.size())},
  };
}

AvrBoard::AvrBoard(const std::string& elf_path, const Options& options) : options_(options) {
  // simavr's reader trusts every size and offset in the file: it sees only a checked image
  const AvrImage image = ReadAvrImage(elf_path);
  // what elf_read_firmware allocates, freed however the constructor ends
  struct Image : elf_firmware_t {
    Image() : elf_firmware_t{} {}
    ~Image() {
      std::free(flash);
      std::free(eeprom);
      std::free(fuse);
      std::free(lockbits);
      for (uint32_t i = 0; i < symbolcount; ++i) std::free(symbol[i]);
      std::free(symbol);
    }
  } fw;
  avr_global_logger_set(&Logger);
  // the image's own AVR_MCU section wins over the link's parameters
  stats_.mcu = image.mcu.empty() ? options.mcu : image.mcu;
  stats_.f_cpu_hz = image.f_cpu_hz ? image.f_cpu_hz : options.f_cpu_hz;
  avr_ = avr_make_mcu_by_name(stats_.mcu.c_str());
  UNIMOUSE_THROW_UNLESS(avr_ != nullptr,
                        elf_path + ": simavr does not know the MCU '" + stats_.mcu + "'");
  Boards().emplace_back(avr_, this);
  // a constructor that throws runs no destructor
  struct Undo {
    AvrBoard* board;
    ~Undo() {
      if (board != nullptr) board->Release();
    }
  } undo{this};
  avr_init(avr_);
  avr_->log = LOG_ERROR;
  WidenMemories(avr_);
  // simavr aborts on an image larger than the part's flash, copies fuses unchecked, and the
  // symbols below say where to read RAM
  CheckAvrImageFits(image,
                    {stats_.mcu, avr_->flashend + 1u, avr_->ioend + 1u, avr_->ramend,
                     avr_->e2end + 1u, static_cast<uint32_t>(sizeof(avr_->fuse))},
                    elf_path);
  UNIMOUSE_THROW_UNLESS(elf_read_firmware(elf_path.c_str(), &fw) == 0 && fw.flashsize > 0,
                        elf_path + ": not an AVR .elf image");
  fw.frequency = stats_.f_cpu_hz;
  // a trace (VCD) would be a file written outside the run's directory
  fw.tracecount = 0;
  avr_load_firmware(avr_, &fw);
  avr_->frequency = stats_.f_cpu_hz;

  // lock-step: never wait for the wall clock while the firmware sleeps
  avr_->sleep = [](avr_t*, avr_cycle_count_t) {};
  run_ = avr_->run;
  uint32_t flags = 0;
  avr_ioctl(avr_, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~(AVR_UART_FLAG_POLL_SLEEP | AVR_UART_FLAG_STDIO);
  avr_ioctl(avr_, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  uart_in_ = avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  UNIMOUSE_THROW_UNLESS(uart_in_ != nullptr, stats_.mcu + " has no UART0");
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          &OnOutput, this);
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON), &OnXon,
                          this);
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                          &OnXoff, this);

  for (const AvrImage::Symbol& symbol : image.symbols) {
    if (symbol.function) {
      functions_[symbol.value] = {symbol.size, symbol.name};
    } else if (symbol.value >= kDataOffset && symbol.value < kDataOffset + 0x10000) {
      data_symbols_[symbol.name] = symbol.value - kDataOffset;
    }
  }
  ram_end_ = avr_->ramend;
  const int64_t data_start = DataSymbol("__data_start");
  ram_start_ = data_start >= 0 ? static_cast<uint32_t>(data_start) : avr_->ioend + 1u;
  // without symbols, the image's sizes say where the data ends
  int64_t heap_start = DataSymbol("__heap_start");
  if (heap_start < 0) heap_start = DataSymbol("_end");
  data_top_ =
      heap_start >= 0 ? static_cast<uint32_t>(heap_start) : ram_start_ + fw.datasize + fw.bsssize;
  brkval_ = DataSymbol("__brkval");
  stats_.sram_bytes = ram_end_ + 1 - ram_start_;
  stats_.static_bytes = data_top_ - ram_start_;
  undo.board = nullptr;
}

AvrBoard::~AvrBoard() { Release(); }

void AvrBoard::Release() {
  std::erase_if(Boards(), [this](const auto& b) { return b.second == this; });
  if (avr_ != nullptr) FreeMcu(avr_);
  avr_ = nullptr;
}

std::string AvrBoard::FunctionAt(uint32_t pc) const {
  auto it = functions_.upper_bound(pc);
  if (it == functions_.begin()) return "";
  --it;
  // a size of 0 (hand-written assembly) claims everything up to the next symbol
  if (it->second.size != 0 && pc >= it->first + it->second.size) return "";
  return it->second.name;
}

int64_t AvrBoard::DataSymbol(const std::string& name) const {
  const auto it = data_symbols_.find(name);
  return it == data_symbols_.end() ? int64_t{-1} : int64_t{it->second};
}

uint64_t AvrBoard::cycle() const { return avr_->cycle; }

uint32_t AvrBoard::pc() const { return avr_->pc; }

uint8_t AvrBoard::reset_flags() const { return avr_->data[kMcusr]; }

uint32_t AvrBoard::CyclesPerBit() const {
  const uint8_t* d = avr_->data;
  const uint32_t ubrr = d[kUbrr0l] | (d[kUbrr0h] & 0x0F) << 8;
  return (ubrr + 1) * (d[kUcsr0a] & 0x02 ? 8 : 16);
}

uint32_t AvrBoard::Baud() const { return stats_.f_cpu_hz / CyclesPerBit(); }

uint32_t AvrBoard::CyclesPerByte() const {
  const uint8_t* d = avr_->data;
  const int size = (d[kUcsr0c] >> 1 & 3) | (d[kUcsr0b] & 0x04);
  static constexpr int kDataBits[] = {5, 6, 7, 8, 8, 8, 8, 9};
  const int stop_bits = 1 + (d[kUcsr0c] >> 3 & 1);
  // start, data, a parity bit (simavr always counts one) and stop bits
  return CyclesPerBit() * static_cast<uint32_t>(1 + kDataBits[size] + 1 + stop_bits);
}

void AvrBoard::Stop(const std::string& why) {
  if (!fault_.empty()) return;
  char where[96];
  const std::string function = FunctionAt(avr_->pc);
  std::snprintf(where, sizeof(where), " at pc 0x%05x (%s), t=%.6f s", avr_->pc,
                function.empty() ? "no symbol" : function.c_str(),
                static_cast<double>(avr_->cycle) / stats_.f_cpu_hz);
  fault_ = "the emulated " + stats_.mcu + " stopped: " + why + where;
}

void AvrBoard::NoteSp() {
  const uint8_t* d = avr_->data;
  min_sp_ = static_cast<uint16_t>(d[R_SPL] | d[R_SPH] << 8);
  uint32_t heap_top = data_top_;
  if (brkval_ >= 0) {
    const uint32_t brk = d[brkval_] | d[brkval_ + 1] << 8;
    if (brk > heap_top) heap_top = brk;
  }
  stats_.heap_bytes = heap_top - data_top_;
  stats_.stack_max_bytes = min_sp_ < ram_end_ ? ram_end_ - min_sp_ : 0;
  stats_.ram_high_water_bytes = stats_.static_bytes + stats_.heap_bytes + stats_.stack_max_bytes;
  // the stack's lowest byte is SP + 1
  if (min_sp_ + 1u < heap_top) {
    char why[160];
    std::snprintf(why, sizeof(why),
                  "its stack (SP 0x%04x) ran into the data and heap below 0x%04x: RAM high-water "
                  "%u of %u bytes",
                  min_sp_, heap_top, stats_.ram_high_water_bytes, stats_.sram_bytes);
    Stop(why);
  }
}

std::string AvrBoard::RunUntilTime(double time_s) {
  return RunUntil(static_cast<uint64_t>(std::llround(time_s * stats_.f_cpu_hz)));
}

std::string AvrBoard::RunUntil(uint64_t target) {
  if (!fault_.empty() || target <= avr_->cycle) return fault_;
  const double cpu0 = ThreadCpu_s();
  target_ = target;
  // a sleeping MCU skips to its next timer: one at the boundary keeps it from going past
  avr_cycle_timer_register(avr_, target - avr_->cycle, &StepEnd, this);
  while (avr_->cycle < target && fault_.empty()) {
    if (avr_->run != run_) {
      // simavr's watchdog has put its reset in place of the next run step
      if (!options_.resets_restart) {
        Stop("the watchdog reset it");
        break;
      }
      avr_run(avr_);
      AfterReset("the watchdog");
      continue;
    }
    const int before = avr_->state;
    const uint64_t cycle = avr_->cycle;
    const int state = avr_run(avr_);
    if (before == cpu_Running) {
      ++stats_.instructions;
    } else if (before == cpu_Sleeping) {
      stats_.sleep_cycles += avr_->cycle - cycle;
    }
    if ((avr_->data[R_SPL] | avr_->data[R_SPH] << 8) < min_sp_) NoteSp();
    if (state == cpu_Done) {
      Stop("it went to sleep with interrupts off, so nothing can wake it");
    } else if (state == cpu_Crashed || state == cpu_Stopped) {
      Stop("it crashed (" + (last_error_.empty() ? std::string("simavr stopped it") : last_error_) +
           ")");
    } else if (avr_->pc == 0) {
      Stop("it jumped to address 0, a restart without a reset");
    }
  }
  stats_.host_cpu_s += ThreadCpu_s() - cpu0;
  return fault_;
}

uint64_t AvrBoard::StepEnd(avr_t*, uint64_t, void*) { return 0; }

void AvrBoard::Reset(ResetCause cause) {
  const char* what = cause == ResetCause::kBrownOut ? "a brown-out" : "its reset pin";
  if (!fault_.empty()) return;
  if (!options_.resets_restart) {
    Stop(std::string("it was reset by ") + what);
    return;
  }
  avr_reset(avr_);
  avr_->data[kMcusr] |= cause == ResetCause::kBrownOut ? kBorf : kExtrf;
  AfterReset(what);
}

void AvrBoard::AfterReset(const std::string& cause) {
  // avr_reset cleared every cycle timer, the line's and the step's, and the UART's registers
  resets_.push_back(cause);
  to_mcu_.clear();
  ends_write_.clear();
  line_busy_ = false;
  receiver_on_ = false;
  fifo_full_ = false;
  mark_pending_ = false;
  walk_ = Walk::kId;
  if (target_ > avr_->cycle) avr_cycle_timer_register(avr_, target_ - avr_->cycle, &StepEnd, this);
}

std::vector<std::string> AvrBoard::TakeResets() { return std::exchange(resets_, {}); }

void AvrBoard::Write(std::span<const uint8_t> bytes) {
  if (bytes.empty()) return;
  receiver_on_ = avr_->data[kUcsr0b] & 0x10;
  // nothing listens before Serial.begin(); the line does not wait for it either
  if (!receiver_on_) {
    stats_.before_receiver_on += bytes.size();
    return;
  }
  if (to_mcu_.size() + bytes.size() > options_.queue_bytes) {
    stats_.dropped_to_mcu += bytes.size();
    NoteOnce(told_line_full_,
             "bytes for the board are being lost: its serial line at " + std::to_string(Baud()) +
                 " baud carries fewer than the simulator sends" +
                 (Baud() < 1000000 ? " (the library opens Serial at UNIMOUSE_BAUD, 1000000)" : ""));
    return;
  }
  to_mcu_.insert(to_mcu_.end(), bytes.begin(), bytes.end());
  ends_write_.insert(ends_write_.end(), bytes.size() - 1, false);
  ends_write_.push_back(true);
  StartLine();
}

void AvrBoard::StartLine() {
  if (line_busy_ || to_mcu_.empty()) return;
  line_busy_ = true;
  avr_cycle_timer_register(avr_, 1, &FeedByte, this);
}

uint64_t AvrBoard::FeedByte(avr_t* avr, uint64_t when, void* param) {
  auto* b = static_cast<AvrBoard*>(param);
  if (b->to_mcu_.empty()) {
    b->line_busy_ = false;
    return 0;
  }
  const uint8_t byte = b->to_mcu_.front();
  const bool ends = b->ends_write_.front();
  b->to_mcu_.pop_front();
  b->ends_write_.pop_front();
  const uint32_t per_byte = b->CyclesPerByte();
  b->stats_.baud = b->Baud();
  b->receiver_on_ = avr->data[kUcsr0b] & 0x10;
  if (!b->receiver_on_) {
    ++b->stats_.before_receiver_on;
  } else {
    // the UART counts a byte it has no room for as an overrun (logged, see Logger)
    const uint64_t overruns = b->stats_.rx_overruns;
    avr_raise_irq(b->uart_in_, byte);
    if (b->stats_.rx_overruns == overruns) {
      ++b->stats_.bytes_to_mcu;
    } else {
      ++b->stats_.dropped_to_mcu;
      b->NoteOnce(b->told_overrun_,
                  "bytes for the board are being lost: its UART received a byte before the "
                  "firmware had read the one before (interrupts off for too long?)");
    }
    if (ends) {
      b->mark_cycle_ = when + per_byte;
      b->mark_pending_ = true;
    }
  }
  return when + per_byte;
}

void AvrBoard::OnOutput(avr_irq_t*, uint32_t value, void* param) {
  auto* b = static_cast<AvrBoard*>(param);
  const uint64_t now = b->avr_->cycle;
  const uint32_t per_byte = b->CyclesPerByte();
  // the transmitter holds one byte in its shift register and one in UDR; a third is lost
  if (b->tx_free_at_ > now + per_byte) {
    ++b->stats_.dropped_from_mcu;
    return;
  }
  const uint64_t arrival = std::max(now, b->tx_free_at_) + per_byte;
  b->tx_free_at_ = arrival;
  if (b->from_mcu_.size() >= (1u << 16)) {
    ++b->stats_.dropped_from_mcu;
    return;
  }
  b->from_mcu_.emplace_back(static_cast<uint8_t>(value), arrival);
  b->WalkOutgoing(static_cast<uint8_t>(value), arrival);
}

void AvrBoard::OnXon(avr_irq_t*, uint32_t value, void* param) {
  auto* b = static_cast<AvrBoard*>(param);
  if (value) b->fifo_full_ = false;
  b->receiver_on_ = b->avr_->data[kUcsr0b] & 0x10;
}

void AvrBoard::OnXoff(avr_irq_t*, uint32_t value, void* param) {
  static_cast<AvrBoard*>(param)->fifo_full_ = value != 0;
}

void AvrBoard::WalkOutgoing(uint8_t byte, uint64_t arrival) {
  bool complete = false;
  switch (walk_) {
    case Walk::kId: {
      const int size = unimouse_payload_size(byte);
      walk_command_ = std::find(options_.command_ids.begin(), options_.command_ids.end(), byte) !=
                      options_.command_ids.end();
      walk_text_after_ = byte == UNIMOUSE_ID_DEBUG_VALUE;
      if (size >= 0) {
        walk_need_ = size;
        walk_ = size > 0 ? Walk::kFixed : Walk::kId;
        complete = size == 0;
      } else if (byte == UNIMOUSE_ID_DEBUG_PATH) {
        walk_ = Walk::kPathCount;
      } else if (byte == UNIMOUSE_ID_DEBUG_VALUE) {
        walk_need_ = 4;
        walk_ = Walk::kFixed;
      } else if (size == UNIMOUSE_FRAME_VARIABLE) {
        walk_ = Walk::kText;
      }
      break;
    }
    case Walk::kFixed:
      if (--walk_need_ == 0) {
        walk_ = walk_text_after_ ? Walk::kText : Walk::kId;
        complete = !walk_text_after_;
      }
      break;
    case Walk::kText:
      if (byte == 0) walk_ = Walk::kId;
      break;
    case Walk::kPathCount:
      walk_need_ = 2 * byte;
      walk_ = byte > 0 ? Walk::kFixed : Walk::kId;
      break;
  }
  if (complete && walk_command_ && mark_pending_ && arrival > mark_cycle_) {
    stats_.latency_cycles.push_back(static_cast<uint32_t>(arrival - mark_cycle_));
    mark_pending_ = false;
  }
}

void AvrBoard::Read(std::vector<uint8_t>& out, size_t max_bytes) {
  const uint64_t now = avr_->cycle;
  while (max_bytes > 0 && !from_mcu_.empty() && from_mcu_.front().second <= now) {
    out.push_back(from_mcu_.front().first);
    from_mcu_.pop_front();
    ++stats_.bytes_from_mcu;
    --max_bytes;
  }
}

AvrBoardStats AvrBoard::stats() const {
  AvrBoardStats s = stats_;
  s.cycles = avr_->cycle;
  return s;
}

void AvrBoard::Logger(avr_t* avr, int level, const char* format, va_list ap) {
  if (level > LOG_ERROR || avr == nullptr) return;
  for (const auto& [mcu, board] : Boards()) {
    if (mcu != avr) continue;
    char text[256];
    std::vsnprintf(text, sizeof(text), format, ap);
    std::string line = text;
    // simavr colours its errors
    for (size_t at; (at = line.find('\x1b')) != std::string::npos;) {
      const size_t end = line.find('m', at);
      line.erase(at, end == std::string::npos ? std::string::npos : end - at + 1);
    }
    while (!line.empty() && (line.back() == '\n' || line.back() == ' ')) line.pop_back();
    if (line.find("RX buffer overrun") != std::string::npos) {
      ++board->stats_.rx_overruns;
    } else if (line.find("Invalid Opcode") != std::string::npos) {
      board->Stop("it ran an invalid instruction");
    } else {
      board->last_error_ = line;
    }
    return;
  }
}

}  // namespace unimouse::link
