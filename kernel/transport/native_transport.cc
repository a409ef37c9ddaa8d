// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware program on this machine, started by the link and talking on its stdin and stdout;
// stopped when the link goes. It runs in lock-step from the first step, so that its runs repeat
// exactly.
#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "stream_transport.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

class NativeTransport final : public StreamTransport {
 public:
  explicit NativeTransport(const std::string& command) : command_(command) {
    UNIMOUSE_THROW_UNLESS(!command.empty(), "native needs a program: native:PATH");
    // words of the command become the arguments; no shell in between
    std::vector<std::string> words;
    for (size_t at = 0; at < command.size();) {
      const size_t end = std::min(command.find(' ', at), command.size());
      if (end > at) words.push_back(command.substr(at, end - at));
      at = end + 1;
    }
    UNIMOUSE_THROW_UNLESS(!words.empty(), "native needs a program: native:PATH");
    const std::string& program = words[0];
    UNIMOUSE_THROW_UNLESS(::access(program.c_str(), X_OK) == 0,
                          program + ": no such program, or it cannot be run");
    int sockets[2];
    UNIMOUSE_THROW_UNLESS(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) == 0,
                          "cannot make a socket pair for the firmware");
    // its standard error is its text: the link logs it line by line
    int text[2];
    if (::pipe2(text, O_CLOEXEC) != 0) {
      ::close(sockets[0]);
      ::close(sockets[1]);
      throw RuntimeFault("cannot make a pipe for the firmware's text");
    }
    std::vector<char*> argv;
    for (auto& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    // in lock-step the simulator and the firmware never run at the same time: on one core each
    // hands over to the other with a plain context switch, while across two cores every step
    // pays two cross-core wake-ups (3x slower on a virtual machine, docs/performance.md)
    const bool share_cpu = ::sched_getaffinity(0, sizeof(own_cpus_), &own_cpus_) == 0;
    cpu_set_t one_cpu;
    CPU_ZERO(&one_cpu);
    if (share_cpu) CPU_SET(::sched_getcpu(), &one_cpu);
    child_ = ::fork();
    if (child_ == 0) {
      if (share_cpu) ::sched_setaffinity(0, sizeof(one_cpu), &one_cpu);
      ::dup2(sockets[1], 0);
      ::dup2(sockets[1], 1);
      ::dup2(text[1], 2);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(sockets[1]);
    ::close(text[1]);
    text_fd_ = text[0];
    ::fcntl(text_fd_, F_SETFL, O_NONBLOCK);
    if (child_ < 0) ::close(sockets[0]);
    UNIMOUSE_THROW_UNLESS(child_ > 0, "cannot start " + program);
    pinned_ = share_cpu && ::sched_setaffinity(0, sizeof(one_cpu), &one_cpu) == 0;
    Adopt(sockets[0]);
  }
  ~NativeTransport() override {
    // a firmware never ends by itself: ask it to stop, then insist
    CloseStream();
    if (text_fd_ >= 0) ::close(text_fd_);
    if (pinned_) ::sched_setaffinity(0, sizeof(own_cpus_), &own_cpus_);
    if (child_ <= 0) return;
    if (ended_) return;
    ::kill(child_, SIGTERM);
    for (int i = 0; i < 100; ++i) {
      if (::waitpid(child_, nullptr, WNOHANG) == child_) return;
      ::usleep(10000);
    }
    ::kill(child_, SIGKILL);
    ::waitpid(child_, nullptr, 0);
  }

  std::string Failure() const override {
    // the socket closes as the program exits, a moment before it can be waited for; a program
    // still connected is alive (or hangs) and is not waited for at all
    for (int i = 0; !ended_ && !Connected() && i < 100; ++i) {
      int status = 0;
      if (::waitpid(child_, &status, WNOHANG) == child_) {
        ended_ = true;
        if (WIFSIGNALED(status)) {
          failure_ = "the firmware crashed: " + FirmwareSignalText(WTERMSIG(status));
        } else {
          failure_ = "the firmware exited with code " + std::to_string(WEXITSTATUS(status));
        }
      } else {
        ::usleep(10000);
      }
    }
    return failure_;
  }

  std::string Describe() const override {
    return "firmware process " + command_ + " (pid " + std::to_string(child_) + ")";
  }
  bool lockstep_from_start() const override { return true; }

  void TakeText(std::vector<std::string>& lines) override {
    char buffer[4096];
    // bounded like the link's reads: a program that prints without end cannot hold a step
    for (size_t total = 0; total < kTextPerRead_bytes;) {
      const ssize_t n = ::read(text_fd_, buffer, sizeof(buffer));
      if (n <= 0) break;
      total += static_cast<size_t>(n);
      partial_.append(buffer, static_cast<size_t>(n));
    }
    size_t from = 0;
    for (size_t end; (end = partial_.find('\n', from)) != std::string::npos; from = end + 1) {
      lines.push_back(partial_.substr(from, end - from));
    }
    partial_.erase(0, from);
    // a line without its end is shown in pieces rather than held without bound
    if (partial_.size() >= kLongestLine_bytes) {
      lines.push_back(partial_);
      partial_.clear();
    }
  }

 private:
  static constexpr size_t kTextPerRead_bytes = 64 * 1024;
  static constexpr size_t kLongestLine_bytes = 1000;

  std::string command_;
  pid_t child_ = -1;
  int text_fd_ = -1;     // the read end of the program's standard error
  std::string partial_;  // its text after the last whole line
  cpu_set_t own_cpus_;   // the simulator thread's cores before the firmware shared one
  bool pinned_ = false;  // whether the simulator thread runs on the firmware's core
  // how the program ended, once it has been waited for
  mutable bool ended_ = false;
  mutable std::string failure_;
};

}  // namespace

std::unique_ptr<Transport> OpenNative(const std::string& command) {
  return std::make_unique<NativeTransport>(command);
}

}  // namespace unimouse::link
