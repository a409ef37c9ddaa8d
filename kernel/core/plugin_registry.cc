// SPDX-License-Identifier: GPL-3.0-or-later
#include "plugin_registry.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <utility>

#include "install_paths.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

std::string MujocoVersionText(int v) {
  return std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." + std::to_string(v % 10);
}

void SplitInto(const std::string& list, std::vector<std::string>& out) {
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ':')) {
    if (!item.empty()) out.push_back(item);
  }
}

}  // namespace

std::string ParamKindName(int kind) {
  switch (kind) {
    case UNIMOUSE_PARAM_NUMBER:
      return "number";
    case UNIMOUSE_PARAM_INTEGER:
      return "integer";
    case UNIMOUSE_PARAM_BOOL:
      return "bool";
    case UNIMOUSE_PARAM_STRING:
      return "string";
  }
  return "?";
}

std::string ParamNumberText(double v) {
  std::ostringstream out;
  out << std::setprecision(10) << v;
  return out.str();
}

std::string ParamDefaultText(const unimouse_param& p) {
  if (p.required) return "required";
  if (p.kind == UNIMOUSE_PARAM_STRING) {
    return p.default_string && *p.default_string ? std::string("`") + p.default_string + "`" : "";
  }
  if (p.kind == UNIMOUSE_PARAM_BOOL) return p.default_number != 0 ? "true" : "false";
  return ParamNumberText(p.default_number);
}

std::string ParamRangeText(const unimouse_param& p) {
  std::string range;
  if (std::isfinite(p.min) || std::isfinite(p.max)) {
    range = (p.min_exclusive ? "(" : "[") + ParamNumberText(p.min) + ", " + ParamNumberText(p.max) +
            "]";
  }
  if (p.choices) range += (range.empty() ? "one of " : ", one of ") + std::string(p.choices);
  return range;
}

std::string UnitOfName(std::string_view name) {
  // longest first: "_nm_per_a" before "_a"
  static constexpr std::pair<std::string_view, std::string_view> kSuffixes[] = {
      {"_nm_s_per_rad", "N m s/rad"},
      {"_dps_per_rt_hz", "deg/s/sqrt(Hz)"},
      {"_g_per_rt_hz", "g/sqrt(Hz)"},
      {"_lsb_per_dps", "LSB/(deg/s)"},
      {"_lsb_per_g", "LSB/g"},
      {"_rad_per_s", "rad/s"},
      {"_m_per_s", "m/s"},
      {"_nm_per_a", "N m/A"},
      {"_kg_m2", "kg m^2"},
      {"_nm_s", "N m s"},
      {"_counts_sd", "counts"},
      {"_bytes", "bytes"},
      {"_bits", "bits"},
      {"_ohm", "ohm"},
      {"_deg", "deg"},
      {"_dps", "deg/s"},
      {"_rad", "rad"},
      {"_hz", "Hz"},
      {"_kg", "kg"},
      {"_g", "g (9.80665 m/s^2)"},
      {"_nm", "N m"},
      {"_m", "m"},
      {"_s", "s"},
      {"_v", "V"},
      {"_a", "A"},
      {"_n", "N"},
      {"_h", "H"},
  };
  for (const auto& [suffix, unit] : kSuffixes) {
    if (name.ends_with(suffix)) return std::string(unit);
  }
  return "";
}

const unimouse_plugin_info* LoadPluginLibrary(const std::string& path) {
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    throw InputError(path + ": cannot load plugin library: " + dlerror());
  }
  const auto entry = reinterpret_cast<unimouse_plugin_entry>(dlsym(handle, UNIMOUSE_PLUGIN_SYMBOL));
  const unimouse_plugin_info* info = entry ? entry() : nullptr;
  const std::string rebuild = "; rebuild it against this unimouse";
  if (entry == nullptr) {
    throw InputError(path + " is not a unimouse plugin: it does not export " +
                     UNIMOUSE_PLUGIN_SYMBOL);
  }
  if (info == nullptr) {
    throw InputError(path + " is not a usable unimouse plugin: " + UNIMOUSE_PLUGIN_SYMBOL +
                     " returned no table");
  }
  if (info->abi_version != UNIMOUSE_ABI_VERSION) {
    throw InputError(path + " was built for plugin ABI version " +
                     std::to_string(info->abi_version) + ", but this unimouse uses version " +
                     std::to_string(UNIMOUSE_ABI_VERSION) + rebuild);
  }
  // tables only grow at the end: an older plugin's shorter type table is widened on adding
  if (info->size < sizeof(unimouse_plugin_info) ||
      info->component_type_size < UNIMOUSE_COMPONENT_TYPE_V1_SIZE) {
    throw InputError(path + " was built with an older plugin header (its tables are " +
                     std::to_string(info->size) + " and " +
                     std::to_string(info->component_type_size) + " bytes, this unimouse needs " +
                     std::to_string(sizeof(unimouse_plugin_info)) + " and " +
                     std::to_string(UNIMOUSE_COMPONENT_TYPE_V1_SIZE) + ")" + rebuild);
  }
  if (info->mujoco_version != mj_version()) {
    throw InputError(path + " was built against MuJoCo " + MujocoVersionText(info->mujoco_version) +
                     ", but this unimouse runs MuJoCo " + MujocoVersionText(mj_version()) +
                     rebuild);
  }
  for (int i = 0; i < info->ntype; ++i) {
    const unimouse_component_type* t = info->types[i];
    if (t == nullptr || t->size < UNIMOUSE_COMPONENT_TYPE_V1_SIZE || t->name == nullptr ||
        t->create == nullptr || t->bind == nullptr || t->destroy == nullptr) {
      throw InputError(path + ": component type #" + std::to_string(i) +
                       " is incomplete (it needs a name, create, bind and destroy)" + rebuild);
    }
  }
  return info;
}

std::vector<std::string> PluginSearchPath(const std::string& option_path) {
  std::vector<std::string> dirs;
  SplitInto(option_path, dirs);
  if (const char* env = std::getenv("UNIMOUSE_PLUGIN_PATH")) SplitInto(env, dirs);
  dirs.push_back(PluginDirectory());
  return dirs;
}

void PluginRegistry::Add(const unimouse_component_type* type, const std::string& library) {
  const auto known = entries_.find(type->name);
  if (known != entries_.end() && known->second.original == type) return;
  // a table from an older header is copied into a whole one: what it lacks reads as NULL
  const unimouse_component_type* whole = type;
  if (type->size < sizeof(unimouse_component_type)) {
    unimouse_component_type& copy = widened_.emplace_back();
    std::memcpy(&copy, type, type->size);
    copy.size = sizeof(copy);
    whole = &copy;
  }
  auto [it, fresh] = entries_.emplace(type->name, Entry{whole, library, type});
  if (!fresh) {
    throw InputError(library + ": component type '" + type->name + "' is already provided by " +
                     it->second.library);
  }
}

void PluginRegistry::AddStatic(const unimouse_component_type* type) { Add(type, "built-in"); }

void PluginRegistry::AddLibrary(const std::string& path) {
  const unimouse_plugin_info* info = LoadPluginLibrary(path);
  for (int i = 0; i < info->ntype; ++i) Add(info->types[i], path);
}

void PluginRegistry::AddSearchPath(const std::vector<std::string>& directories) {
  namespace fs = std::filesystem;
  for (const auto& dir : directories) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    std::vector<std::string> libraries;
    for (const auto& file : fs::directory_iterator(dir, ec)) {
      const std::string name = file.path().filename().string();
      if (name.starts_with("libunimouse_") && name.ends_with(".so")) {
        libraries.push_back(file.path().string());
      }
    }
    std::sort(libraries.begin(), libraries.end());
    for (const auto& library : libraries) {
      // the first directory that provides a library name wins, as with PATH
      const std::string base = fs::path(library).filename().string();
      const bool shadowed = std::any_of(entries_.begin(), entries_.end(), [&](const auto& e) {
        return fs::path(e.second.library).filename().string() == base;
      });
      if (!shadowed) AddLibrary(library);
    }
  }
}

const PluginRegistry::Entry* PluginRegistry::Find(const std::string& name) const {
  const auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::string DescribePlugins(const PluginRegistry& registry) {
  std::ostringstream out;
  if (registry.entries().empty()) out << "no component types found\n";
  for (const auto& [name, entry] : registry.entries()) {
    const unimouse_component_type& t = *entry.type;
    out << name << "  (" << entry.library << ")\n  " << (t.summary ? t.summary : "") << "\n";
    out << "  period: "
        << (t.default_period_s > 0 ? ParamNumberText(t.default_period_s) + " s" : "every step")
        << " unless period_s is given\n";
    for (int i = 0; i < t.nparam; ++i) {
      const unimouse_param& p = t.params[i];
      const std::string default_text = ParamDefaultText(p);
      out << "  - " << p.name << " (" << ParamKindName(p.kind) << ")"
          << (p.required ? ", " : ", default ") << (default_text.empty() ? "''" : default_text);
      const std::string range = ParamRangeText(p);
      if (!range.empty()) out << ", " << range;
      out << ": " << (p.doc ? p.doc : "") << "\n";
    }
  }
  return out.str();
}

}  // namespace unimouse
