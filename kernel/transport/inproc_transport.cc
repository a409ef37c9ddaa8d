// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware built as a module (NAME.so beside each PC-built example) loaded into the
// simulator's process and run on a stack of its own: its Serial reads and writes queues here,
// and it hands control back whenever it waits for input, to be resumed when the simulator has
// sent the next step. No threads and no clock between the two, so a step costs little more than
// its physics and runs repeat exactly. A fault, exit() or a hang in the firmware ends the
// firmware, not the simulator: a handler on its own stack abandons the firmware's context.
#include <dlfcn.h>
#include <setjmp.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <boost/context/detail/fcontext.hpp>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>

#include "transport.h"
#include "unimouse/errors.h"
#include "unimouse_inproc.h"

namespace unimouse::link {
namespace {

namespace fctx = boost::context::detail;

constexpr size_t kStack_bytes = size_t{8} << 20;  // what a program's main thread gets
constexpr size_t kGuard_bytes = 64 << 10;         // an overflow faults here, not in the heap
constexpr long kWatchdogTick_ms = 100;
constexpr int kFaults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

// what the signal handlers share with the firmware that runs now (one at a time, on the thread
// that opened the modules)
struct Escape {
  sigjmp_buf to;
  volatile sig_atomic_t in_firmware = 0;
  volatile sig_atomic_t signal = 0;  // what abandoned the firmware; -1: the watchdog
  void* volatile address = nullptr;
  volatile sig_atomic_t resumes = 0;  // entries into the firmware, for the watchdog
  volatile sig_atomic_t seen_resumes = 0;
  volatile sig_atomic_t stuck_ticks = 0;
  volatile sig_atomic_t limit_ticks = 50;
};
Escape escape;

struct sigaction previous[NSIG];
int open_modules = 0;
pid_t owner_thread = 0;
timer_t watchdog;
std::set<std::string> loaded;  // modules in use, or left loaded by a firmware that failed

[[noreturn]] void Abandon() {
  escape.in_firmware = 0;
  siglongjmp(escape.to, 1);
}

void OnFault(int sig, siginfo_t* info, void*) {
  if (!escape.in_firmware) {
    // the simulator's own fault: as if this handler were not there
    sigaction(sig, &previous[sig], nullptr);
    return;
  }
  escape.signal = sig;
  escape.address = info->si_addr;
  Abandon();
}

void OnWatchdog(int, siginfo_t*, void*) {
  if (!escape.in_firmware || escape.resumes != escape.seen_resumes) {
    escape.seen_resumes = escape.resumes;
    escape.stuck_ticks = 0;
    return;
  }
  escape.stuck_ticks = escape.stuck_ticks + 1;
  if (escape.stuck_ticks < escape.limit_ticks) return;
  escape.signal = -1;
  Abandon();
}

int WatchdogSignal() { return SIGRTMIN + 5; }

// the handlers and the watchdog live while a module is open
void InstallGuards() {
  stack_t alt{};
  if (sigaltstack(nullptr, &alt) == 0 && (alt.ss_flags & SS_DISABLE) != 0) {
    static std::vector<char> alt_stack(256 << 10);
    alt.ss_sp = alt_stack.data();
    alt.ss_size = alt_stack.size();
    alt.ss_flags = 0;
    sigaltstack(&alt, nullptr);
  }
  struct sigaction action {};
  action.sa_sigaction = &OnFault;
  // no deferral: the handler leaves by a jump, and the signal must not stay blocked after it
  action.sa_flags = SA_SIGINFO | SA_ONSTACK | SA_NODEFER;
  sigemptyset(&action.sa_mask);
  for (int sig : kFaults) sigaction(sig, &action, &previous[sig]);
  action.sa_sigaction = &OnWatchdog;
  action.sa_flags |= SA_RESTART;
  sigaction(WatchdogSignal(), &action, &previous[WatchdogSignal()]);
  sigevent event{};
  event.sigev_notify = SIGEV_THREAD_ID;
  event.sigev_signo = WatchdogSignal();
  event._sigev_un._tid = owner_thread;
  UNIMOUSE_THROW_UNLESS(timer_create(CLOCK_MONOTONIC, &event, &watchdog) == 0,
                        "cannot start the watchdog for a firmware module");
  const timespec tick{0, kWatchdogTick_ms * 1000000};
  const itimerspec every{tick, tick};
  timer_settime(watchdog, 0, &every, nullptr);
}

void RemoveGuards() {
  timer_delete(watchdog);
  for (int sig : kFaults) sigaction(sig, &previous[sig], nullptr);
  sigaction(WatchdogSignal(), &previous[WatchdogSignal()], nullptr);
}

// a fault at an address says where; the other signals say what
std::string SignalText(int sig, void* address) {
  if (sig != SIGSEGV && sig != SIGBUS) return FirmwareSignalText(sig);
  char text[128];
  std::snprintf(
      text, sizeof(text), "%s (%s 0x%lx)", sig == SIGSEGV ? "SIGSEGV" : "SIGBUS",
      reinterpret_cast<uintptr_t>(address) < 4096 ? "null pointer? address" : "bad address",
      static_cast<unsigned long>(reinterpret_cast<uintptr_t>(address)));
  return text;
}

// a copy of a module under a name of its own, to load a second time with globals of its own
// (dlopen gives the module already loaded for the same file); the caller removes it once loaded
std::string PrivateCopy(const std::string& path) {
  std::string name = (std::filesystem::temp_directory_path() / "unimouse-firmware-XXXXXX.so");
  const int fd = ::mkstemps(name.data(), 3);
  UNIMOUSE_THROW_UNLESS(
      fd >= 0, path + ": cannot copy the module for a second robot (" + std::strerror(errno) + ")");
  ::close(fd);
  std::error_code ec;
  std::filesystem::copy_file(path, name, std::filesystem::copy_options::overwrite_existing, ec);
  if (ec) ::unlink(name.c_str());
  UNIMOUSE_THROW_UNLESS(
      !ec, path + ": cannot copy the module for a second robot (" + ec.message() + ")");
  return name;
}

class InprocTransport final : public Transport {
 public:
  explicit InprocTransport(const std::string& path) {
    UNIMOUSE_THROW_UNLESS(!path.empty(), "inproc needs a firmware module: inproc:PATH.so");
    std::error_code ec;
    path_ = std::filesystem::canonical(path, ec).string();
    UNIMOUSE_THROW_UNLESS(!ec, path + ": no such firmware module");
    const pid_t thread = static_cast<pid_t>(::syscall(SYS_gettid));
    UNIMOUSE_THROW_UNLESS(open_modules == 0 || owner_thread == thread,
                          "firmware modules run on one thread: " + path +
                              " cannot be opened while another thread runs one");
    // a module already loaded (another robot's, or one a failed firmware left behind) is loaded
    // again from a copy: each robot's firmware has globals of its own
    copy_ = loaded.contains(path_);
    const std::string opened = copy_ ? PrivateCopy(path_) : path_;
    handle_ = ::dlopen(opened.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (copy_) ::unlink(opened.c_str());
    UNIMOUSE_THROW_UNLESS(handle_ != nullptr, path + ": not a firmware module: " + ::dlerror());
    entry_ = reinterpret_cast<unimouse_inproc_main>(::dlsym(handle_, UNIMOUSE_INPROC_ENTRY));
    if (entry_ == nullptr) ::dlclose(handle_);
    UNIMOUSE_THROW_UNLESS(entry_ != nullptr,
                          path + ": not a firmware module (no " UNIMOUSE_INPROC_ENTRY ")");
    void* memory = ::mmap(nullptr, kStack_bytes, PROT_READ | PROT_WRITE,
                          MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (memory == MAP_FAILED) ::dlclose(handle_);
    UNIMOUSE_THROW_UNLESS(memory != MAP_FAILED, "no memory for the firmware's stack");
    stack_ = static_cast<char*>(memory);
    ::mprotect(stack_, kGuard_bytes, PROT_NONE);
    fw_ = fctx::make_fcontext(stack_ + kStack_bytes, kStack_bytes - kGuard_bytes, &Enter);
    host_ = {sizeof(host_), UNIMOUSE_INPROC_VERSION, this, &HostRead, &HostWrite, &HostSuspend,
             &HostExit};
    if (!copy_) loaded.insert(path_);
    if (open_modules++ == 0) {
      owner_thread = thread;
      InstallGuards();
    }
  }

  ~InprocTransport() override {
    // a firmware that failed may have left anything behind: its module stays loaded, unrun
    if (failure_.empty() && copy_) {
      ::dlclose(handle_);
    } else if (failure_.empty()) {
      ::dlclose(handle_);
      void* still = ::dlopen(path_.c_str(), RTLD_NOW | RTLD_NOLOAD);
      if (still != nullptr) {
        ::dlclose(still);
      } else {
        loaded.erase(path_);
      }
    }
    ::munmap(stack_, kStack_bytes);
    if (--open_modules == 0) RemoveGuards();
  }

  void Read(std::vector<uint8_t>& out, size_t max_bytes) override {
    // a firmware that waits for the next step has nothing to do until it is sent
    if (!(awaiting_step_ && in_pos_ == in_.size())) Resume();
    const size_t n = std::min(max_bytes, out_.size());
    out.insert(out.end(), out_.begin(), out_.begin() + static_cast<ptrdiff_t>(n));
    out_.erase(out_.begin(), out_.begin() + static_cast<ptrdiff_t>(n));
  }

  bool WaitReadable(std::chrono::milliseconds timeout) override {
    escape.limit_ticks = static_cast<sig_atomic_t>(
        std::max<long>(1, (timeout.count() + kWatchdogTick_ms - 1) / kWatchdogTick_ms));
    // said in whole watchdog ticks: the link's timeout, less what the step has used
    limit_s_ = static_cast<double>(escape.limit_ticks) * kWatchdogTick_ms / 1000;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (out_.empty()) {
      // a firmware that waits for a step while the simulator waits for it cannot answer
      if (ended_ || (awaiting_step_ && in_pos_ == in_.size())) return false;
      Resume();
      if (out_.empty() && std::chrono::steady_clock::now() >= deadline) return false;
    }
    return true;
  }

  size_t Write(std::span<const uint8_t> bytes) override {
    if (ended_) return bytes.size();
    if (in_pos_ == in_.size()) {
      in_.clear();
      in_pos_ = 0;
    }
    in_.insert(in_.end(), bytes.begin(), bytes.end());
    return bytes.size();
  }

  bool Connected() const override { return !ended_; }
  std::string Describe() const override {
    return "firmware module " + path_ + " (in the simulator's process)";
  }
  bool lockstep_from_start() const override { return true; }
  std::string Failure() const override { return failure_; }

 private:
  // runs the firmware until it waits for input, ends or is abandoned
  void Resume() {
    if (ended_) return;
    escape.resumes = escape.resumes + 1;
    escape.in_firmware = 1;
    if (sigsetjmp(escape.to, 0) == 0) {
      const fctx::transfer_t back = fctx::jump_fcontext(fw_, this);
      fw_ = back.fctx;
      escape.in_firmware = 0;
      return;
    }
    // a signal abandoned the firmware mid-step: its stack is never used again
    ended_ = true;
    char text[96];
    std::snprintf(text, sizeof(text), "the firmware did not finish its step within %g s", limit_s_);
    failure_ = escape.signal == -1
                   ? std::string(text)
                   : "the firmware crashed: " + SignalText(escape.signal, escape.address);
  }

  static void Enter(fctx::transfer_t from) {
    auto* self = static_cast<InprocTransport*>(from.data);
    self->sim_ = from.fctx;
    try {
      self->entry_(&self->host_);
      self->failure_ = "the firmware's main returned";
    } catch (const std::exception& e) {
      self->failure_ = std::string("the firmware threw an exception: ") + e.what();
    } catch (...) {
      self->failure_ = "the firmware threw an exception";
    }
    self->Leave();
  }

  // the firmware's end: back to the simulator for good
  [[noreturn]] void Leave() {
    ended_ = true;
    fctx::jump_fcontext(sim_, nullptr);
    __builtin_unreachable();
  }

  static size_t HostRead(void* self, uint8_t* bytes, size_t max) {
    auto* t = static_cast<InprocTransport*>(self);
    const size_t n = std::min(max, t->in_.size() - t->in_pos_);
    if (n == 0) return 0;  // an empty queue may have no storage to copy from
    std::memcpy(bytes, t->in_.data() + t->in_pos_, n);
    t->in_pos_ += n;
    return n;
  }
  static void HostWrite(void* self, const uint8_t* bytes, size_t size) {
    auto* t = static_cast<InprocTransport*>(self);
    t->out_.insert(t->out_.end(), bytes, bytes + size);
  }
  static void HostSuspend(void* self, int awaiting_step) {
    auto* t = static_cast<InprocTransport*>(self);
    t->awaiting_step_ = awaiting_step != 0;
    t->sim_ = fctx::jump_fcontext(t->sim_, nullptr).fctx;
    t->awaiting_step_ = false;
  }
  static void HostExit(void* self, int code) {
    auto* t = static_cast<InprocTransport*>(self);
    t->failure_ = "the firmware called exit(" + std::to_string(code) + ")";
    t->Leave();
  }

  std::string path_;
  bool copy_ = false;  // loaded from a private copy: path_ was loaded already
  void* handle_ = nullptr;
  unimouse_inproc_main entry_ = nullptr;
  unimouse_inproc_host host_{};
  char* stack_ = nullptr;
  fctx::fcontext_t fw_ = nullptr;   // where the firmware goes on
  fctx::fcontext_t sim_ = nullptr;  // where the simulator waits for it
  std::vector<uint8_t> in_, out_;
  size_t in_pos_ = 0;
  bool awaiting_step_ = false;
  bool ended_ = false;
  double limit_s_ = 5;
  std::string failure_;
};

}  // namespace

std::unique_ptr<Transport> OpenInproc(const std::string& path) {
  return std::make_unique<InprocTransport>(path);
}

}  // namespace unimouse::link
