// SPDX-License-Identifier: GPL-3.0-or-later
// Trace logger: every period it records the sim time, the robot's ground truth (pose, forward
// speed, yaw rate), chosen joint speeds and chosen signals, as CSV or JSON lines. It also records
// every text line components logged (a firmware's log channel among them) with its sim time:
// inline in JSONL, in a sibling `<name>_messages.csv` for CSV. Files go to the run's output
// directory; rows are flushed every 100 records, and at the end of the run, however it ends,
// it writes the lines logged since its last period and flushes.
#ifndef UNIMOUSE_PLUGINS_LOGGER_H_
#define UNIMOUSE_PLUGINS_LOGGER_H_

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct LoggerParams {
  std::string path = "trace.csv";
  std::string format = "csv";
  std::string body = "chassis";
  std::string joints;
  std::string signals;

  template <class V>
  void Visit(V& v) {
    v("path", path, "file to write, relative to the run's output directory");
    v("format", format, "csv or jsonl (one JSON object per line)", param::OneOf{"csv|jsonl"});
    v("body", body, "body whose ground-truth pose and speeds it records; '' for none");
    v("joints", joints, "comma-separated hinge joints whose speeds it records, rad/s");
    v("signals", signals, "comma-separated signals it records");
  }
};

class Logger final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.logger";
  static constexpr const char* kSummary = "trace logger: ground truth, signals and text lines";
  static constexpr double kDefaultPeriod_s = 0.01;
  using Params = LoggerParams;

  explicit Logger(Params params) : p_(std::move(params)) {}
  void Bind(BindContext& ctx) override;
  /// Opens the trace files.
  void Start() override;
  void Sense(const SenseContext& ctx) const override;
  void Finish(const SenseContext& ctx) const override;

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  using File = std::unique_ptr<std::FILE, FileCloser>;

  void WriteMessages(const SenseContext& ctx) const;

  const Params p_;
  int body_ = -1;
  std::vector<std::string> columns_;
  std::vector<int> joint_dofs_;
  std::vector<SignalId> signals_;
  std::string path_;  // the trace file, inside the output directory
  // files are resources, not state: rebuilt on load, never part of a snapshot
  File trace_;
  File messages_;
  mutable int unflushed_ = 0;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_LOGGER_H_
