// SPDX-License-Identifier: GPL-3.0-or-later
#include "mujoco_guard.h"

#include <mujoco/mujoco.h>

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct GuardFrame {
  std::jmp_buf back;
  char message[1024];
};

// the innermost guard of this thread; MuJoCo calls its callback on the caller's thread
thread_local GuardFrame* innermost = nullptr;

[[noreturn]] void OnMujocoError(const char* message) {
  GuardFrame* frame = innermost;
  if (frame == nullptr) {
    // a call that should have been guarded: there is no safe way back, so end as a fault does
    std::fprintf(stderr, "unimouse: error: MuJoCo error outside a guarded call: %s\n", message);
    std::fflush(nullptr);
    std::_Exit(kExitRuntimeFault);
  }
  std::snprintf(frame->message, sizeof(frame->message), "%s", message);
  std::longjmp(frame->back, 1);
}

}  // namespace

void InstallMujocoHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = [](const char* message) { std::cerr << "MuJoCo: " << message << "\n"; };
    mju_user_error = OnMujocoError;
  });
}

void GuardMujoco(void (*call)(void*), void* arg) {
  InstallMujocoHandlers();
  GuardFrame frame;
  GuardFrame* const outer = innermost;
  innermost = &frame;
  // glibc's setjmp saves no signal mask: no system call
  if (setjmp(frame.back) == 0) {
    // an exception from inside (an allocation, a callback) leaves no guard behind on its way
    try {
      call(arg);
    } catch (...) {
      innermost = outer;
      throw;
    }
    innermost = outer;
    return;
  }
  innermost = outer;
  throw RuntimeFault(std::string("MuJoCo error: ") + frame.message);
}

}  // namespace unimouse
