// SPDX-License-Identifier: GPL-3.0-or-later
#include "component_config.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

std::string Text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

void CheckRange(const unimouse_param& p, double v, const YamlNode& node, const std::string& who) {
  const bool below = p.min_exclusive ? !(v > p.min) : v < p.min;
  if (!below && v <= p.max) return;
  std::string rule;
  if (std::isfinite(p.min) && std::isfinite(p.max)) {
    rule = std::string("within ") + (p.min_exclusive ? "(" : "[") + Text(p.min) + ", " +
           Text(p.max) + "]";
  } else if (std::isfinite(p.min)) {
    rule = (p.min_exclusive ? "greater than " : "at least ") + Text(p.min);
  } else {
    rule = "at most " + Text(p.max);
  }
  node.Fail(who + p.name + " must be " + rule + ", not " + node.scalar);
}

}  // namespace

unimouse_config ValidateParams(const unimouse_component_type& type, const ComponentSpec& spec) {
  const std::string who = "component '" + spec.name + "' (" + type.name + "): ";
  const YamlNode& params = spec.params;
  if (params.kind != YamlNode::Kind::kNull && !params.IsMap()) {
    params.Fail(who + "params must be a map of name: value lines");
  }

  // every given key must be declared
  std::vector<std::string> declared;
  for (int i = 0; i < type.nparam; ++i) declared.emplace_back(type.params[i].name);
  for (const auto& [key, value] : params.entries) {
    bool known = false;
    for (const auto& d : declared) known = known || d == key.scalar;
    if (!known) {
      const std::string near = NearestWord(key.scalar, declared);
      key.Fail(who + "unknown parameter '" + key.scalar + "'" +
               (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
  }

  unimouse_config config;
  for (int i = 0; i < type.nparam; ++i) {
    const unimouse_param& p = type.params[i];
    const YamlNode* value = nullptr;
    for (const auto& [key, v] : params.entries) {
      if (key.scalar == p.name) value = &v;
    }
    if (value == nullptr) {
      if (p.required) {
        const YamlNode& where = params.kind == YamlNode::Kind::kNull ? spec.params : params;
        throw InputError(where.location.ToString() + ": " + who + "missing parameter '" + p.name +
                         "' (" + (p.doc ? p.doc : "") + ")");
      }
      if (p.kind == UNIMOUSE_PARAM_STRING) {
        config.strings[p.name] = p.default_string ? p.default_string : "";
      } else {
        config.numbers[p.name] = p.default_number;
      }
      continue;
    }
    const std::string what = who + p.name;
    config.given.emplace_back(p.name);
    // a command-line option has no line in a file
    if (value->location.line > 0) config.from_data_file.emplace_back(p.name);
    switch (p.kind) {
      case UNIMOUSE_PARAM_NUMBER: {
        const double v = value->AsNumber(what);
        CheckRange(p, v, *value, who);
        config.numbers[p.name] = v;
        break;
      }
      case UNIMOUSE_PARAM_INTEGER: {
        const double v = value->AsInteger(what);
        CheckRange(p, v, *value, who);
        config.numbers[p.name] = v;
        break;
      }
      case UNIMOUSE_PARAM_BOOL:
        config.numbers[p.name] = value->AsBool(what) ? 1 : 0;
        break;
      case UNIMOUSE_PARAM_STRING: {
        const std::string& s = value->AsString(what);
        if (p.choices != nullptr) {
          const std::string choices = std::string("|") + p.choices + "|";
          if (s.empty() || choices.find("|" + s + "|") == std::string::npos) {
            value->Fail(what + " must be one of " + p.choices + ", not '" + s + "'");
          }
        }
        config.strings[p.name] = s;
        break;
      }
      default:
        value->Fail(what + ": the plugin declares an unknown parameter kind");
    }
  }
  return config;
}

const unimouse_host& ConfigHost() {
  static const unimouse_host host = [] {
    unimouse_host h{};
    h.size = sizeof(unimouse_host);
    h.config_number = [](const unimouse_config* cfg, const char* name) -> double {
      const auto it = cfg->numbers.find(name);
      return it == cfg->numbers.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
    };
    h.config_string = [](const unimouse_config* cfg, const char* name) -> const char* {
      const auto it = cfg->strings.find(name);
      return it == cfg->strings.end() ? "" : it->second.c_str();
    };
    h.config_given = [](const unimouse_config* cfg, const char* name) -> int {
      for (const auto& g : cfg->given) {
        if (g == name) return 1;
      }
      return 0;
    };
    h.config_from_data_file = [](const unimouse_config* cfg, const char* name) -> int {
      for (const auto& g : cfg->from_data_file) {
        if (g == name) return 1;
      }
      return 0;
    };
    h.log = [](void*, int, const char* message) { std::cerr << message << "\n"; };
    return h;
  }();
  return host;
}

}  // namespace unimouse
