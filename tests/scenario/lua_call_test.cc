// SPDX-License-Identifier: GPL-3.0-or-later
// The Lua boundary on a bare Lua state: a C++ body's exception becomes a Lua error at the
// script's line, only after every C++ object the body made is gone; arguments are read without
// running metamethods; errors from helpers in the prelude name the script's line.
#include "lua_call.h"

#include <gtest/gtest.h>
#include <lua5.4/lauxlib.h>
#include <lua5.4/lualib.h>

#include <string>

namespace unimouse {
namespace {

// counts the objects alive, so that a test can see every one destroyed
struct Tracked {
  static inline int alive = 0;
  Tracked() { ++alive; }
  Tracked(const Tracked&) = delete;
  ~Tracked() { --alive; }
};

class LuaBoundaryTest : public ::testing::Test {
 protected:
  LuaBoundaryTest() : L_(luaL_newstate()) { luaL_openlibs(L_); }
  ~LuaBoundaryTest() override { lua_close(L_); }

  // adds a global function `name` run by `body`
  void Define(const char* name, LuaBody body) {
    PushLuaFunction(L_, body, name, "sim.");
    lua_setglobal(L_, name);
  }

  // runs `code` as the file `chunk` ("@file.lua", "=prelude.lua"); returns its error, or ""
  std::string Run(const std::string& code, const char* chunk = "@script.lua") {
    if (luaL_loadbufferx(L_, code.data(), code.size(), chunk, "t") != LUA_OK ||
        lua_pcall(L_, 0, 0, 0) != LUA_OK) {
      std::string error = ErrorText(L_, -1);
      lua_pop(L_, 1);
      return error;
    }
    return "";
  }

  lua_State* L_;
};

TEST_F(LuaBoundaryTest, AThrownExceptionBecomesALuaErrorAtTheScriptsLine) {
  Define("explode", [](LuaCall&) -> int { throw std::runtime_error("the motor is on fire"); });
  EXPECT_EQ(Run("local x = 1\nexplode()\n"), "script.lua:2: the motor is on fire");
}

TEST_F(LuaBoundaryTest, EveryCppObjectOfTheBodyIsGoneBeforeTheErrorIsRaised) {
  Define("explode", [](LuaCall& call) -> int {
    const Tracked held;
    const std::string text(1000, 'x');  // on the heap: a leak if a longjmp skipped it
    call.Fail("failed while holding " + std::to_string(Tracked::alive) + " object");
  });
  EXPECT_EQ(Run("explode()"), "script.lua:1: failed while holding 1 object");
  EXPECT_EQ(Tracked::alive, 0);
}

TEST_F(LuaBoundaryTest, AnExceptionOfAnyTypeIsCaught) {
  Define("explode", [](LuaCall&) -> int { throw 42; });
  EXPECT_EQ(Run("explode()"), "script.lua:1: an unknown C++ exception");
}

TEST_F(LuaBoundaryTest, ALuaErrorCanBeCaughtByTheScriptAndTheStateGoesOn) {
  Define("explode", [](LuaCall&) -> int { throw std::runtime_error("once"); });
  EXPECT_EQ(Run("local ok, e = pcall(explode)\n"
                "assert(not ok and e == 'once', e)\n"
                "ok, e = pcall(function() explode() end)\n"
                "assert(e == 'script.lua:3: once', e)\n"),
            "");
}

TEST_F(LuaBoundaryTest, BadArgumentsAreNamedAsLuaNamesThem) {
  Define("hud_set", [](LuaCall& call) -> int {
    call.CheckInteger(1);
    return 0;
  });
  EXPECT_EQ(Run("hud_set('one')"),
            "script.lua:1: bad argument #1 to 'sim.hud_set' (number expected, got string)");
  EXPECT_EQ(Run("hud_set()"),
            "script.lua:1: bad argument #1 to 'sim.hud_set' (number expected, got no value)");
  EXPECT_EQ(
      Run("hud_set(1.5)"),
      "script.lua:1: bad argument #1 to 'sim.hud_set' (number has no integer representation)");
}

TEST_F(LuaBoundaryTest, FieldsAreReadWithoutRunningMetamethods) {
  Define("robot_place", [](LuaCall& call) -> int {
    call.CheckTable(1);
    lua_pushnumber(call.state(), call.NumberField(1, "x_m"));
    return 1;
  });
  // a metamethod that would fail is never run: the field is simply missing
  EXPECT_EQ(Run("robot_place(setmetatable({}, { __index = function() error('ran') end }))"),
            "script.lua:1: sim.robot_place: missing field 'x_m'");
  EXPECT_EQ(Run("robot_place({ x_m = 'far' })"),
            "script.lua:1: sim.robot_place: field 'x_m' must be a number");
  EXPECT_EQ(Run("robot_place({ x_m = 1/0 })"),
            "script.lua:1: sim.robot_place: field 'x_m' must be finite");
  EXPECT_EQ(Run("assert(robot_place({ x_m = 0.5 }) == 0.5)"), "");
}

TEST_F(LuaBoundaryTest, ATostringThatFailsIsTheScriptsErrorWithItsOwnLine) {
  Define("print", [](LuaCall& call) -> int {
    const std::string text = call.ToText(1);
    lua_pushstring(call.state(), text.c_str());
    return 1;
  });
  EXPECT_EQ(Run("local bad = setmetatable({}, { __tostring = function()\n"
                "  error('cannot say')\n"
                "end })\n"
                "print(bad)\n"),
            "script.lua:2: cannot say");
  EXPECT_EQ(Run("assert(print(12) == '12')"), "");
}

TEST_F(LuaBoundaryTest, AnErrorRaisedInThePreludeNamesTheFirstCallerOutsideIt) {
  Define("wall_add", [](LuaCall& call) -> int { call.Fail("a wall needs a length"); });
  // a helper in the prelude that calls C++: the error names the script, not the helper
  ASSERT_EQ(Run("function helper() wall_add() end", kPreludeChunk), "");
  EXPECT_EQ(Run("\n\nhelper()\n"), "script.lua:3: a wall needs a length");
}

TEST_F(LuaBoundaryTest, AnErrorObjectThatIsNotTextIsNamedByItsType) {
  EXPECT_EQ(Run("error({})"), "(error object is a table value)");
  EXPECT_EQ(Run("error(7)"), "7");
}

}  // namespace
}  // namespace unimouse
