// SPDX-License-Identifier: GPL-3.0-or-later
#include "sysid_log.h"

#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::fit {
namespace {

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    std::string_view field =
        line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t'))
      field.remove_prefix(1);
    while (!field.empty() &&
           (field.back() == ' ' || field.back() == '\t' || field.back() == '\r')) {
      field.remove_suffix(1);
    }
    fields.push_back(field);
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace

SysidLog ReadSysidLog(const std::string& path) {
  const std::string text = ReadTextFile(path);
  SysidLog log;
  log.file = path;
  const auto fail = [&](int line, const std::string& reason) {
    throw InputError(path + ":" + std::to_string(line) + ": " + reason);
  };

  std::map<std::string, size_t> column;  // name -> index in a row
  std::vector<std::vector<double>*> targets;
  std::vector<size_t> target_column;
  int line_number = 0;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const std::vector<std::string_view> fields = SplitFields(line);

    if (column.empty()) {
      for (size_t i = 0; i < fields.size(); ++i) column.emplace(std::string(fields[i]), i);
      for (const char* name : kRequiredColumns) {
        if (!column.contains(name)) {
          fail(line_number, std::string("the header has no column '") + name +
                                "' (a log needs time_s, left_command, right_command, battery_v, "
                                "left_counts, right_counts)");
        }
      }
      std::vector<double>* named[] = {&log.time_s,    &log.left_command, &log.right_command,
                                      &log.battery_v, &log.left_counts,  &log.right_counts};
      for (size_t i = 0; i < std::size(kRequiredColumns); ++i) {
        targets.push_back(named[i]);
        target_column.push_back(column.at(kRequiredColumns[i]));
      }
      if (column.contains(kGyroColumn)) {
        targets.push_back(&log.gyro_z_rad_s);
        target_column.push_back(column.at(kGyroColumn));
      }
      continue;
    }

    if (log.rows() >= kMaxLogRows) {
      fail(line_number, "more than " + std::to_string(kMaxLogRows) + " rows");
    }
    if (fields.size() < column.size()) {
      fail(line_number, std::to_string(fields.size()) + " fields where the header names " +
                            std::to_string(column.size()));
    }
    for (size_t t = 0; t < targets.size(); ++t) {
      const std::string_view field = fields[target_column[t]];
      double value = 0;
      const auto [end_ptr, error] =
          std::from_chars(field.data(), field.data() + field.size(), value);
      if (field.empty() || error != std::errc() || end_ptr != field.data() + field.size() ||
          !std::isfinite(value)) {
        std::string name;
        for (const auto& [n, i] : column) {
          if (i == target_column[t]) name = n;
        }
        fail(line_number, name + " '" + std::string(field) + "' is not a finite number");
      }
      targets[t]->push_back(value);
    }
    if (log.rows() >= 2 && !(log.time_s.back() > log.time_s[log.rows() - 2])) {
      fail(line_number, "time_s goes from " + std::to_string(log.time_s[log.rows() - 2]) + " to " +
                            std::to_string(log.time_s.back()) +
                            ": time must increase from row to row");
    }
    log.line.push_back(line_number);
  }
  if (column.empty()) fail(1, "empty: a log needs a header and rows");
  return log;
}

}  // namespace unimouse::fit
