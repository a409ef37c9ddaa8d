// SPDX-License-Identifier: GPL-3.0-or-later
// The Lua boundary. Every C++ function that Lua calls (the sim.* functions, the sandbox's own,
// the instruction hook, the host's steps while loading) is a LuaBody, and the one way in is
// RunBody: it runs the body, catches whatever C++ exception it throws, lets every C++ object go
// out of scope, and only then raises the Lua error. A Lua error is a longjmp: it must never jump
// over a live C++ object, and no C++ exception may unwind through Lua's C frames.
//
// Bodies keep to one rule: they never raise a Lua error themselves. They read their arguments
// through LuaCall, whose readers throw, read tables raw (no metamethods run), and run Lua code
// only under protection (LuaCall::ToText). The Lua API calls left in a body push plain values,
// which can fail only when the machine's memory runs out: a state's own limits (LuaMemory)
// never refuse a body.
#ifndef UNIMOUSE_SCENARIO_LUA_CALL_H_
#define UNIMOUSE_SCENARIO_LUA_CALL_H_

#include <lua5.4/lua.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace unimouse {

/// The chunk name the prelude is loaded under. Errors raised from C++ name the first caller
/// outside it: the scenario's file:line, not the helper's.
inline constexpr const char* kPreludeChunk = "=prelude.lua";

/// A Lua error thrown in C++: RunBody raises its message as the Lua error. The message gets the
/// calling script's `file:line: ` in front, as luaL_error would put it, unless `located` says it
/// has its place already.
class ScriptError : public std::runtime_error {
 public:
  explicit ScriptError(const std::string& message, bool located = false)
      : std::runtime_error(message), located_(located) {}
  /// Whether the message starts with its file:line already.
  bool located() const { return located_; }

 private:
  bool located_;
};

/// The memory of one Lua state, made with lua_newstate(LuaMemory::Allocate, &memory): what it
/// holds at most (`limit_bytes`), and how much a script may allocate in all between two resets
/// (`volume_bytes`: building strings is work the instruction count does not see). Limits hold
/// only while a script runs: the host's own allocations (RunBody's bodies, the host between
/// calls) are never refused, so a refusal is always a Lua memory error raised in script code,
/// never a longjmp out of C++.
class LuaMemory {
 public:
  LuaMemory(size_t limit_bytes, size_t volume_bytes)
      : limit_bytes_(limit_bytes), volume_bytes_(volume_bytes) {}
  LuaMemory(const LuaMemory&) = delete;
  LuaMemory& operator=(const LuaMemory&) = delete;

  /// The lua_Alloc: `ud` is the LuaMemory.
  static void* Allocate(void* ud, void* block, size_t old_size, size_t new_size);
  /// The state's LuaMemory, or null when it allocates some other way.
  static LuaMemory* Of(lua_State* L);

  /// Sets whether script code runs now (limits hold), returning the previous setting.
  bool SetScriptRunning(bool running) {
    const bool was = script_running_;
    script_running_ = running;
    return was;
  }
  /// Starts a new allocation volume, as the host calls into Lua again.
  void ResetVolume() {
    volume_used_bytes_ = 0;
    volume_spent_ = false;
  }
  /// Whether the volume ran out since the last reset (and allocations are refused since).
  bool volume_spent() const { return volume_spent_; }
  size_t limit_bytes() const { return limit_bytes_; }
  size_t volume_bytes() const { return volume_bytes_; }
  size_t in_use_bytes() const { return in_use_bytes_; }

 private:
  const size_t limit_bytes_;
  const size_t volume_bytes_;
  size_t in_use_bytes_ = 0;
  size_t volume_used_bytes_ = 0;
  bool volume_spent_ = false;
  bool script_running_ = false;
};

class LuaCall;

/// A C++ function behind a Lua one: reads its arguments through `call`, pushes its results and
/// returns how many. Throws on a bad argument or a failure; never raises a Lua error itself.
/// Its own type, not lua_CFunction, so that it cannot be handed to Lua without RunBody.
using LuaBody = int (*)(LuaCall& call);

/// Pushes a Lua function that runs `body` through RunBody; `prefix` and `name` together are the
/// name its errors use ("sim." and "wall_add").
void PushLuaFunction(lua_State* L, LuaBody body, const char* name, const char* prefix = "");

/// Runs `body` as the Lua function `name` and returns its result count. When it throws, raises
/// the exception's message as a Lua error, after the exception and every object the body made
/// are gone. Never returns then.
int RunBody(lua_State* L, LuaBody body, const char* name);

/// Returns `body` as a C function with no upvalues, for the host's own steps run with lua_pcall
/// (pushing it allocates nothing, so nothing can fail before the protected call). It runs the
/// body through RunBody, as every function Lua calls does.
template <LuaBody kBody>
int HostStep(lua_State* L) {
  return RunBody(L, kBody, "the host");
}

/// Returns "file:line: " of the first function from stack level `level` up that is not in the
/// prelude, or "" when that one is a C function; the file's whole path, where Lua's messages
/// (and RunBody's, which follow them) shorten a long one. In a hook, level 0 is the running
/// function.
std::string ScriptLine(lua_State* L, int level);

/// Returns the error value at `index` as text, without running any Lua code: a string or a
/// number as it is, anything else as "(error object is a table value)".
std::string ErrorText(lua_State* L, int index);

/// What a body sees: its arguments, its name, and readers that throw ScriptError in the words
/// Lua uses ("bad argument #1 to 'sim.hud_set' (number expected, got nil)").
class LuaCall {
 public:
  LuaCall(lua_State* L, const char* name) : L_(L), name_(name) {}

  /// The Lua state (or thread) the function runs on.
  lua_State* state() const { return L_; }
  /// The function's name as scripts call it, e.g. "sim.wall_add".
  const char* name() const { return name_; }
  /// Returns how many arguments the function was given.
  int count() const { return lua_gettop(L_); }

  /// Throws ScriptError(message).
  [[noreturn]] void Fail(const std::string& message) const { throw ScriptError(message); }

  /// Whether argument `arg` is absent or nil.
  bool IsNoneOrNil(int arg) const { return lua_type(L_, arg) <= LUA_TNIL; }
  /// Throws unless argument `arg` is a table.
  void CheckTable(int arg) const;
  /// Returns argument `arg` as a number; a numeric string counts, as in Lua.
  double CheckNumber(int arg) const;
  /// Returns argument `arg` as an integer.
  lua_Integer CheckInteger(int arg) const;
  /// Returns argument `arg` as a string; a number counts, as in Lua.
  std::string CheckString(int arg) const;
  /// Returns argument `arg` as a string, in place: valid while the argument is on the stack.
  std::string_view CheckText(int arg) const;
  /// Returns argument `arg` as a string, or `fallback` when it is absent or nil.
  std::string OptString(int arg, const std::string& fallback) const;

  /// Returns the type (LUA_TNIL...) of field `key` of the table argument `table`, read raw.
  int FieldType(int table, const char* key) const;
  /// Returns field `key` of the table argument `table`, a finite number; throws when it is
  /// missing, not a number or not finite.
  double NumberField(int table, const char* key) const;
  /// Returns field `key` as NumberField does, or `fallback` when it is nil.
  double NumberField(int table, const char* key, double fallback) const;
  /// Returns field `key`, an integer, or `fallback` when it is nil.
  lua_Integer IntegerField(int table, const char* key, lua_Integer fallback) const;
  /// Returns field `key`, a string, or `fallback` when it is nil.
  std::string StringField(int table, const char* key, const std::string& fallback) const;

  /// Calls the function under the `nargs` values on top of the stack under protection, leaving
  /// `nresults` results; an error there is thrown as the script's own, with its place.
  void ProtectedCall(int nargs, int nresults) const;
  /// Returns the value at `index` as text, as tostring() gives it: its __tostring runs under
  /// protection, and an error there is thrown as the script's own.
  std::string ToText(int index) const;

 private:
  [[noreturn]] void FailArgument(int arg, const std::string& what) const;
  [[noreturn]] void FailType(int arg, const char* expected) const;
  // pushes field `key` of the table argument, raw, and returns its type
  int PushField(int table, const char* key) const;

  lua_State* L_;
  const char* name_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_LUA_CALL_H_
