// SPDX-License-Identifier: GPL-3.0-or-later
// Parameters are declared once, in a Params struct with a Visit method; the same list gives the
// schema the kernel validates YAML against, reads the validated values, and documents defaults.
//
//   struct DcMotorParams {
//     double resistance_ohm = 16.66667;
//     template <class V> void Visit(V& v) {
//       v("resistance_ohm", resistance_ohm, "armature resistance", param::Positive{});
//     }
//   };
#ifndef UNIMOUSE_PARAMS_H_
#define UNIMOUSE_PARAMS_H_

#include <deque>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "unimouse/plugin_abi.h"

namespace unimouse::param {

/// The YAML must give this parameter; the field's value is not a default.
struct Required {};
/// Strictly greater than zero.
struct Positive {};
/// Zero or more.
struct NonNegative {};
/// Within [min, max].
struct Range {
  double min, max;
};
/// One of a '|'-separated list of words.
struct OneOf {
  const char* choices;
};

/// Builds the C parameter table from a Params struct's Visit list.
class SchemaBuilder {
 public:
  template <class T, class... Constraints>
  void operator()(const char* name, const T& field, const char* doc, Constraints... constraints) {
    unimouse_param p{};
    p.name = name;
    p.doc = doc;
    p.min = -std::numeric_limits<double>::infinity();
    p.max = std::numeric_limits<double>::infinity();
    if constexpr (std::is_same_v<T, bool>) {
      p.kind = UNIMOUSE_PARAM_BOOL;
      p.default_number = field ? 1 : 0;
    } else if constexpr (std::is_integral_v<T>) {
      p.kind = UNIMOUSE_PARAM_INTEGER;
      p.default_number = static_cast<double>(field);
    } else if constexpr (std::is_floating_point_v<T>) {
      p.kind = UNIMOUSE_PARAM_NUMBER;
      p.default_number = field;
    } else {
      static_assert(std::is_same_v<T, std::string>, "parameters are numbers, bools or strings");
      p.kind = UNIMOUSE_PARAM_STRING;
      p.default_string = strings_.emplace_back(field).c_str();
    }
    (Apply(p, constraints), ...);
    params_.push_back(p);
  }

  const std::vector<unimouse_param>& params() const { return params_; }

 private:
  static void Apply(unimouse_param& p, Required) { p.required = 1; }
  static void Apply(unimouse_param& p, Positive) {
    p.min = 0;
    p.min_exclusive = 1;
  }
  static void Apply(unimouse_param& p, NonNegative) { p.min = 0; }
  static void Apply(unimouse_param& p, Range r) {
    p.min = r.min;
    p.max = r.max;
  }
  static void Apply(unimouse_param& p, OneOf o) { p.choices = o.choices; }

  std::vector<unimouse_param> params_;
  std::deque<std::string> strings_;  // stable addresses for default_string
};

/// Names of the parameters the robot file gave; the others kept their defaults. A Params struct
/// with a `given` member of this type receives it (for presets that supply defaults); one with a
/// `from_data_file` member receives the names whose values came from a data file rather than
/// the command line (for values that may start a program).
using GivenSet = std::vector<std::string>;

/// Reads validated values into a Params struct through the host table.
class ConfigReader {
 public:
  ConfigReader(const unimouse_config* cfg, const unimouse_host* host) : cfg_(cfg), host_(host) {}

  const GivenSet& given() const { return given_; }
  const GivenSet& from_data_file() const { return from_data_file_; }

  template <class T, class... Constraints>
  void operator()(const char* name, T& field, const char*, Constraints...) {
    if (host_->config_given(cfg_, name)) given_.emplace_back(name);
    // a host too old to tell is taken to say "from a data file": the careful answer
    if (!UNIMOUSE_HAS_FIELD(host_, unimouse_host, config_from_data_file) ||
        host_->config_from_data_file(cfg_, name)) {
      if (host_->config_given(cfg_, name)) from_data_file_.emplace_back(name);
    }
    if constexpr (std::is_same_v<T, bool>) {
      field = host_->config_number(cfg_, name) != 0;
    } else if constexpr (std::is_arithmetic_v<T>) {
      field = static_cast<T>(host_->config_number(cfg_, name));
    } else {
      field = host_->config_string(cfg_, name);
    }
  }

 private:
  const unimouse_config* cfg_;
  const unimouse_host* host_;
  GivenSet given_;
  GivenSet from_data_file_;
};

/// Returns the items of a comma-separated list parameter, spaces trimmed, empty items dropped.
inline std::vector<std::string> SplitList(const std::string& list) {
  std::vector<std::string> items;
  size_t begin = 0;
  while (begin <= list.size()) {
    size_t end = list.find(',', begin);
    if (end == std::string::npos) end = list.size();
    std::string item = list.substr(begin, end - begin);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) items.push_back(item);
    begin = end + 1;
  }
  return items;
}

/// Returns whether the robot file gave parameter `name`.
inline bool Given(const GivenSet& given, const char* name) {
  for (const auto& g : given) {
    if (g == name) return true;
  }
  return false;
}

}  // namespace unimouse::param

#endif  // UNIMOUSE_PARAMS_H_
