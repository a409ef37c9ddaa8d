// SPDX-License-Identifier: GPL-3.0-or-later
#include "logger.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace unimouse::plugins {
namespace {

constexpr int kFlushEvery = 100;

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string CsvString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c == '\n' || c == '\r' ? ' ' : c;
  }
  return out + "\"";
}

const char* LevelName(int level) {
  switch (level) {
    case UNIMOUSE_LOG_ERROR:
      return "error";
    case UNIMOUSE_LOG_WARNING:
      return "warning";
    case UNIMOUSE_LOG_FIRMWARE:
      return "firmware";
    case UNIMOUSE_LOG_DETAIL:
      return "detail";
  }
  return "info";
}

}  // namespace

void Logger::Bind(BindContext& ctx) {
  const mjModel& m = ctx.model();
  columns_.push_back("time_s");
  if (!p_.body.empty()) {
    body_ = ctx.BodyId(p_.body);
    for (const char* c : {"x_m", "y_m", "yaw_rad", "speed_m_per_s", "yaw_rate_rad_per_s"}) {
      columns_.push_back(c);
    }
  }
  for (const auto& joint : param::SplitList(p_.joints)) {
    const int j = ctx.JointId(joint);
    UNIMOUSE_THROW_UNLESS(m.jnt_type[j] == mjJNT_HINGE, "joint '" + joint + "' is not a hinge");
    joint_dofs_.push_back(m.jnt_dofadr[j]);
    columns_.push_back(joint + "_rad_per_s");
  }
  for (const auto& signal : param::SplitList(p_.signals)) {
    signals_.push_back(ctx.ReadSignal(signal));
    columns_.push_back(signal);
  }

  path_ = ctx.OutputFile(p_.path);
}

void Logger::Start() {
  // files are opened for a run only: checking a robot file writes nothing
  namespace fs = std::filesystem;
  const fs::path path = path_;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  auto open = [](const fs::path& file) {
    File f(std::fopen(file.c_str(), "w"));
    UNIMOUSE_THROW_UNLESS(f != nullptr,
                          file.string() + ": cannot write the log (" + std::strerror(errno) + ")");
    return f;
  };
  trace_ = open(path);
  if (p_.format == "csv") {
    for (size_t i = 0; i < columns_.size(); ++i) {
      std::fprintf(trace_.get(), "%s%s", i ? "," : "", columns_[i].c_str());
    }
    std::fprintf(trace_.get(), "\n");
    fs::path messages = path;
    messages.replace_filename(path.stem().string() + "_messages.csv");
    messages_ = open(messages);
    std::fprintf(messages_.get(), "time_s,level,source,text\n");
  }
}

void Logger::Sense(const SenseContext& ctx) const {
  // a logger that was only checked, never started, has no file
  if (!trace_) return;
  const mjModel& m = ctx.model();
  const mjData& d = ctx.data();
  std::vector<double> row;
  row.reserve(columns_.size());
  row.push_back(ctx.time_s());
  if (body_ >= 0) {
    const double* q = d.xquat + 4 * body_;
    const double yaw =
        std::atan2(2 * (q[0] * q[3] + q[1] * q[2]), 1 - 2 * (q[2] * q[2] + q[3] * q[3]));
    double velocity[6];  // rotation then translation, world axes, at the body's origin
    mj_objectVelocity(&m, &d, mjOBJ_BODY, body_, velocity, 0);
    row.insert(row.end(), {d.xpos[3 * body_], d.xpos[3 * body_ + 1], yaw,
                           velocity[3] * std::cos(yaw) + velocity[4] * std::sin(yaw), velocity[2]});
  }
  for (int dof : joint_dofs_) row.push_back(d.qvel[dof]);
  for (SignalId s : signals_) row.push_back(ctx.Read(s));

  std::FILE* f = trace_.get();
  if (p_.format == "csv") {
    for (size_t i = 0; i < row.size(); ++i) std::fprintf(f, "%s%.17g", i ? "," : "", row[i]);
    std::fprintf(f, "\n");
  } else {
    std::fprintf(f, "{");
    for (size_t i = 0; i < row.size(); ++i) {
      std::fprintf(f, "%s%s:%.17g", i ? "," : "", JsonString(columns_[i]).c_str(), row[i]);
    }
    std::fprintf(f, "}\n");
  }
  WriteMessages(ctx);
  if (++unflushed_ >= kFlushEvery) {
    std::fflush(f);
    if (messages_) std::fflush(messages_.get());
    unflushed_ = 0;
  }
}

void Logger::Finish(const SenseContext& ctx) const {
  if (!trace_) return;
  WriteMessages(ctx);
  std::fflush(trace_.get());
  if (messages_) std::fflush(messages_.get());
}

void Logger::WriteMessages(const SenseContext& ctx) const {
  for (const unimouse_message& msg : ctx.messages()) {
    if (p_.format == "csv") {
      std::fprintf(messages_.get(), "%.17g,%s,%s,%s\n", msg.time_s, LevelName(msg.level),
                   CsvString(msg.source).c_str(), CsvString(msg.text).c_str());
    } else {
      std::fprintf(trace_.get(), "{\"time_s\":%.17g,\"level\":\"%s\",\"source\":%s,\"text\":%s}\n",
                   msg.time_s, LevelName(msg.level), JsonString(msg.source).c_str(),
                   JsonString(msg.text).c_str());
    }
  }
}

}  // namespace unimouse::plugins
