// SPDX-License-Identifier: GPL-3.0-or-later
#include "lua_call.h"

#include <lua5.4/lauxlib.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace unimouse {

namespace {

// longer messages are cut; the array lives on the C stack and needs no destructor
constexpr size_t kMessageSize = 2048;

void KeepMessage(const char* text, char (&message)[kMessageSize]) {
  std::snprintf(message, kMessageSize, "%s", text);
}

// the first non-prelude function from `level` up, when it is Lua code at a known line
bool FindScriptLine(lua_State* L, int level, lua_Debug* ar) {
  for (; lua_getstack(L, level, ar) == 1; ++level) {
    lua_getinfo(L, "Sl", ar);
    if (std::strcmp(ar->source, kPreludeChunk) != 0) return ar->currentline > 0;
  }
  return false;
}

// a file's whole path, where Lua's own messages shorten a long one
const char* SourceName(const lua_Debug& ar) {
  return ar.source[0] == '@' ? ar.source + 1 : ar.short_src;
}

// the one C function Lua sees for every body; its upvalues are the body and its name
int CallBody(lua_State* L) {
  LuaBody body = nullptr;
  std::memcpy(&body, lua_touserdata(L, lua_upvalueindex(1)), sizeof(body));
  return RunBody(L, body, lua_tostring(L, lua_upvalueindex(2)));
}

}  // namespace

void* LuaMemory::Allocate(void* ud, void* block, size_t old_size, size_t new_size) {
  auto& m = *static_cast<LuaMemory*>(ud);
  // with no block, old_size is the kind of object, not a size
  const size_t held = block != nullptr ? old_size : 0;
  if (new_size == 0) {
    std::free(block);
    m.in_use_bytes_ -= held;
    return nullptr;
  }
  const size_t growth = new_size > held ? new_size - held : 0;
  if (m.script_running_ && growth > 0) {
    if (m.volume_spent_ || m.volume_used_bytes_ + growth > m.volume_bytes_) {
      m.volume_spent_ = true;
      return nullptr;
    }
    if (m.in_use_bytes_ + growth > m.limit_bytes_) return nullptr;
  }
  void* grown = std::realloc(block, new_size);
  if (grown == nullptr) return nullptr;
  m.in_use_bytes_ = m.in_use_bytes_ - held + new_size;
  m.volume_used_bytes_ += growth;
  return grown;
}

LuaMemory* LuaMemory::Of(lua_State* L) {
  void* ud = nullptr;
  return lua_getallocf(L, &ud) == &LuaMemory::Allocate ? static_cast<LuaMemory*>(ud) : nullptr;
}

void PushLuaFunction(lua_State* L, LuaBody body, const char* name, const char* prefix) {
  std::memcpy(lua_newuserdatauv(L, sizeof(body), 0), &body, sizeof(body));
  lua_pushfstring(L, "%s%s", prefix, name);
  lua_pushcclosure(L, CallBody, 2);
}

int RunBody(lua_State* L, LuaBody body, const char* name) {
  char message[kMessageSize];
  bool located = false;
  // the host's work is never refused memory: a refusal inside a body would longjmp out of it
  LuaMemory* memory = LuaMemory::Of(L);
  const bool script_was_running = memory != nullptr && memory->SetScriptRunning(false);
  try {
    LuaCall call(L, name);
    const int results = body(call);
    if (memory != nullptr) memory->SetScriptRunning(script_was_running);
    return results;
  } catch (const ScriptError& e) {
    located = e.located();
    KeepMessage(e.what(), message);
  } catch (const std::exception& e) {
    KeepMessage(e.what(), message);
  } catch (...) {
    KeepMessage("an unknown C++ exception", message);
  }

  // the exception and everything the body made are gone: from here a longjmp is safe
  lua_Debug ar;
  if (!located && FindScriptLine(L, 1, &ar)) {
    lua_pushfstring(L, "%s:%d: %s", ar.short_src, ar.currentline, message);
  } else {
    lua_pushstring(L, message);
  }
  if (memory != nullptr) memory->SetScriptRunning(script_was_running);
  return lua_error(L);
}

std::string ScriptLine(lua_State* L, int level) {
  lua_Debug ar;
  if (!FindScriptLine(L, level, &ar)) return "";
  return std::string(SourceName(ar)) + ":" + std::to_string(ar.currentline) + ": ";
}

std::string ErrorText(lua_State* L, int index) {
  switch (lua_type(L, index)) {
    case LUA_TSTRING: {
      size_t size = 0;
      const char* text = lua_tolstring(L, index, &size);
      return std::string(text, size);
    }
    case LUA_TNUMBER: {
      char text[64];
      if (lua_isinteger(L, index)) {
        std::snprintf(text, sizeof(text), LUA_INTEGER_FMT, lua_tointeger(L, index));
      } else {
        std::snprintf(text, sizeof(text), "%.14g", lua_tonumber(L, index));
      }
      return text;
    }
    default:
      return std::string("(error object is a ") + luaL_typename(L, index) + " value)";
  }
}

void LuaCall::FailArgument(int arg, const std::string& what) const {
  throw ScriptError("bad argument #" + std::to_string(arg) + " to '" + name_ + "' (" + what + ")");
}

void LuaCall::FailType(int arg, const char* expected) const {
  const int type = lua_type(L_, arg);
  FailArgument(arg, std::string(expected) + " expected, got " +
                        (type == LUA_TNONE ? "no value" : lua_typename(L_, type)));
}

void LuaCall::CheckTable(int arg) const {
  if (lua_type(L_, arg) != LUA_TTABLE) FailType(arg, "table");
}

double LuaCall::CheckNumber(int arg) const {
  int ok = 0;
  const lua_Number value = lua_tonumberx(L_, arg, &ok);
  if (!ok) FailType(arg, "number");
  return value;
}

lua_Integer LuaCall::CheckInteger(int arg) const {
  int ok = 0;
  const lua_Integer value = lua_tointegerx(L_, arg, &ok);
  if (!ok && lua_isnumber(L_, arg)) FailArgument(arg, "number has no integer representation");
  if (!ok) FailType(arg, "number");
  return value;
}

std::string LuaCall::CheckString(int arg) const { return std::string(CheckText(arg)); }

std::string_view LuaCall::CheckText(int arg) const {
  if (!lua_isstring(L_, arg)) FailType(arg, "string");
  size_t size = 0;
  const char* text = lua_tolstring(L_, arg, &size);
  return {text, size};
}

std::string LuaCall::OptString(int arg, const std::string& fallback) const {
  return IsNoneOrNil(arg) ? fallback : CheckString(arg);
}

int LuaCall::PushField(int table, const char* key) const {
  table = lua_absindex(L_, table);
  lua_pushstring(L_, key);
  return lua_rawget(L_, table);
}

int LuaCall::FieldType(int table, const char* key) const {
  const int type = PushField(table, key);
  lua_pop(L_, 1);
  return type;
}

double LuaCall::NumberField(int table, const char* key) const {
  if (FieldType(table, key) == LUA_TNIL) Fail(std::string(name_) + ": missing field '" + key + "'");
  return NumberField(table, key, 0);
}

double LuaCall::NumberField(int table, const char* key, double fallback) const {
  const int type = PushField(table, key);
  int ok = 0;
  const lua_Number value = lua_tonumberx(L_, -1, &ok);
  lua_pop(L_, 1);
  if (type == LUA_TNIL) return fallback;
  if (!ok) Fail(std::string(name_) + ": field '" + key + "' must be a number");
  if (!std::isfinite(value)) Fail(std::string(name_) + ": field '" + key + "' must be finite");
  return value;
}

lua_Integer LuaCall::IntegerField(int table, const char* key, lua_Integer fallback) const {
  const int type = PushField(table, key);
  int ok = 0;
  const lua_Integer value = lua_tointegerx(L_, -1, &ok);
  lua_pop(L_, 1);
  if (type == LUA_TNIL) return fallback;
  if (!ok) Fail(std::string(name_) + ": field '" + key + "' must be an integer");
  return value;
}

std::string LuaCall::StringField(int table, const char* key, const std::string& fallback) const {
  const int type = PushField(table, key);
  if (type == LUA_TNIL || !lua_isstring(L_, -1)) {
    lua_pop(L_, 1);
    if (type == LUA_TNIL) return fallback;
    Fail(std::string(name_) + ": field '" + key + "' must be a string");
  }
  size_t size = 0;
  const char* text = lua_tolstring(L_, -1, &size);
  std::string value(text, size);
  lua_pop(L_, 1);
  return value;
}

std::string LuaCall::ToText(int index) const {
  // the standard tostring, from the real globals (scripts see only their sandbox)
  index = lua_absindex(L_, index);
  lua_rawgeti(L_, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  lua_pushliteral(L_, "tostring");
  lua_rawget(L_, -2);
  lua_remove(L_, -2);
  lua_pushvalue(L_, index);
  ProtectedCall(1, 1);
  std::string text = ErrorText(L_, -1);
  lua_pop(L_, 1);
  return text;
}

void LuaCall::ProtectedCall(int nargs, int nresults) const {
  // the function called may be the script's own, under its limits
  LuaMemory* memory = LuaMemory::Of(L_);
  const bool script_was_running = memory != nullptr && memory->SetScriptRunning(true);
  const int status = lua_pcall(L_, nargs, nresults, 0);
  if (memory != nullptr) memory->SetScriptRunning(script_was_running);
  if (status == LUA_OK) return;
  std::string message = ErrorText(L_, -1);
  lua_pop(L_, 1);
  throw ScriptError(message, /*located=*/true);
}

}  // namespace unimouse
