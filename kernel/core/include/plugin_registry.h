// SPDX-License-Identifier: GPL-3.0-or-later
// Component types by name, from plugin libraries (loaded with a version handshake) or registered
// statically by the program itself.
#ifndef UNIMOUSE_CORE_PLUGIN_REGISTRY_H_
#define UNIMOUSE_CORE_PLUGIN_REGISTRY_H_

#include <deque>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "unimouse/plugin_abi.h"

namespace unimouse {

/// Checks a plugin library's table against this kernel and returns it; throws InputError with
/// one sentence naming the library and the mismatch. The library stays loaded for the life of
/// the program, since its types may be in use.
const unimouse_plugin_info* LoadPluginLibrary(const std::string& path);

/// Returns the directories searched for plugins, in order: the --plugin-path list, then
/// UNIMOUSE_PLUGIN_PATH, then the install (or build-tree) plugin directory.
std::vector<std::string> PluginSearchPath(const std::string& option_path);

class PluginRegistry {
 public:
  PluginRegistry() = default;
  // entries may point into widened_, whose elements a move keeps in place and a copy would not
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;
  PluginRegistry(PluginRegistry&&) = default;
  PluginRegistry& operator=(PluginRegistry&&) = default;

  struct Entry {
    const unimouse_component_type* type = nullptr;      ///< whole, as this kernel's header has it
    std::string library;                                ///< file it came from, or "built-in"
    const unimouse_component_type* original = nullptr;  ///< as the plugin handed it over
  };

  /// Adds a type compiled into the program.
  void AddStatic(const unimouse_component_type* type);
  /// Loads one library and adds its types.
  void AddLibrary(const std::string& path);
  /// Loads every libunimouse_*.so in the directories, in name order; missing directories are
  /// skipped.
  void AddSearchPath(const std::vector<std::string>& directories);

  /// Returns the type, or nullptr.
  const Entry* Find(const std::string& name) const;
  const std::map<std::string, Entry>& entries() const { return entries_; }

 private:
  void Add(const unimouse_component_type* type, const std::string& library);
  std::map<std::string, Entry> entries_;
  std::deque<unimouse_component_type> widened_;  // whole copies of older, shorter tables
};

/// Returns a parameter kind's name: number, integer, bool or string.
std::string ParamKindName(int kind);
/// Returns a parameter's default as documented: "required", a number, true/false, or the
/// string in backquotes (empty for an empty string).
std::string ParamDefaultText(const unimouse_param& p);
/// Returns a number as the parameter tables show it: up to 10 significant digits.
std::string ParamNumberText(double value);
/// Returns the values a parameter allows beyond its kind: "[0, 10]", "(0, inf]", "one of a|b",
/// or "" for any.
std::string ParamRangeText(const unimouse_param& p);
/// Returns the unit a name's suffix says ("m/s" for speed_m_per_s, "ohm" for resistance_ohm), or
/// "" for a name without one.
std::string UnitOfName(std::string_view name);

/// Returns the plugin table as text: one block per type with its parameters, for `unimouse
/// plugins`.
std::string DescribePlugins(const PluginRegistry& registry);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_PLUGIN_REGISTRY_H_
