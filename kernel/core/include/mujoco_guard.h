// SPDX-License-Identifier: GPL-3.0-or-later
// MuJoCo reports an error by calling its error callback from deep inside its C code, and the
// callback must not return. A C++ exception thrown there would unwind through MuJoCo's C frames,
// which is undefined behaviour. So every call into MuJoCo that can raise an error runs inside
// GuardMujoco: the callback jumps back to the guard (longjmp), out of MuJoCo's frames, and only
// there the error becomes a RuntimeFault. A component's hook runs inside one too, as a backstop
// for the calls a plugin makes to MuJoCo itself: the plugin's own frames are then left without
// unwinding (what they hold is lost), so a plugin should call MuJoCo only where nothing it owns
// is on the stack. The host's own calls a hook reaches (a ray cast) are guarded where they are.
#ifndef UNIMOUSE_CORE_MUJOCO_GUARD_H_
#define UNIMOUSE_CORE_MUJOCO_GUARD_H_

#include <type_traits>
#include <utility>

namespace unimouse {

/// Routes MuJoCo's errors to the guard and its warnings to stderr (never MUJOCO_LOG.TXT or
/// exit(1)); idempotent, and done by the first guard of the process.
void InstallMujocoHandlers();

/// Runs `call(arg)`; an error MuJoCo raises inside it is thrown as RuntimeFault ("MuJoCo error:
/// ...") once out of MuJoCo. Costs no system call.
void GuardMujoco(void (*call)(void*), void* arg);

/// Runs `f()` inside a guard. Nothing between the guard and MuJoCo may own a resource.
template <class F>
void GuardMujoco(F&& f) {
  GuardMujoco([](void* p) { (*static_cast<std::remove_reference_t<F>*>(p))(); },
              const_cast<void*>(static_cast<const void*>(&f)));
}

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_MUJOCO_GUARD_H_
