// SPDX-License-Identifier: GPL-3.0-or-later
#include "fit_commands.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "command_line.h"
#include "fit.h"
#include "install_paths.h"
#include "plugin_registry.h"
#include "robot_patch.h"
#include "sysid_log.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Loaded {
  std::string robot_file;
  RobotSpec robot;
  std::vector<fit::SysidLog> logs;
};

// reads and checks everything before anything is written
Loaded Load(const FitOptions& o) {
  Loaded l;
  l.robot_file = ResolveDataFile(o.robot, "robots/", ".yaml");
  l.robot = LoadRobotSpec(l.robot_file);
  const fit::RobotWiring wiring = fit::WireRobot(l.robot);
  for (const std::string& file : o.logs) {
    l.logs.push_back(fit::ReadSysidLog(file));
    fit::CheckLogFitsRobot(l.logs.back(), l.robot, wiring);
  }
  return l;
}

std::string Name(const fit::ParameterRef& p) { return p.component + "." + p.key; }

// the plots' file names: out_dir/<log's stem>-<channel>-<kind>.png, one stem per log
class PlotNames {
 public:
  PlotNames(const std::string& out_dir, const std::vector<fit::SysidLog>& logs) : dir_(out_dir) {
    std::vector<std::string> files;
    for (const fit::SysidLog& log : logs) files.push_back(log.file);
    stems_ = fit::PlotStems(files);
  }
  std::string operator()(size_t log_index, const std::string& channel, const char* kind) const {
    return dir_ + "/" + stems_.at(log_index) + "-" + channel + "-" + kind + ".png";
  }

 private:
  std::string dir_;
  std::vector<std::string> stems_;
};

}  // namespace

int FitCommand(const FitOptions& o) {
  const Loaded l = Load(o);
  PluginRegistry registry;
  registry.AddSearchPath(PluginSearchPath(o.plugin_path));
  const fit::FitReport report = fit::FitRobot(l.robot, registry, l.logs);

  std::printf(
      "fit of %s to %zu log(s): simulation error by Eigen's Levenberg-Marquardt, %d "
      "iterations, %d replays\n\n",
      l.robot_file.c_str(), l.logs.size(), report.iterations, report.replays);
  std::printf("%-34s %12s %12s  %-27s %s\n", "parameter", "file", "fitted", "95 % interval",
              "identified");
  for (const fit::FittedParameter& p : report.parameters) {
    char interval[64], file[32];
    std::snprintf(interval, sizeof(interval), "[%.6g, %.6g]", p.ci_low, p.ci_high);
    if (fit::ParameterDrawn(l.robot, p.ref)) {
      std::snprintf(file, sizeof(file), "drawn");
    } else {
      std::snprintf(file, sizeof(file), "%.6g", p.file_value);
    }
    std::printf("%-34s %12s %12.6g  %-27s %s\n", Name(p.ref).c_str(), file, p.value, interval,
                p.identified ? "yes" : "no: the logs cannot pin it; the file's value kept");
  }
  std::printf("%-34s %12s %12s  %-27s %s\n", "each motor's damping_nm_s_per_rad", "", "", "",
              "no: wheel speeds alone cannot tell it from Kt and Ra; the file's value kept");
  std::printf("%-34s %12s %12s  %-27s %s\n", "each wheel joint's armature_kg_m2", "", "", "",
              "no: it enters the speed's time constant only with Ra; the file's value kept");
  if (report.gyro_not_used) {
    std::printf("%-34s %12s %12s  %-27s %s\n", "the gyro's bias and scale error", "", "", "",
                "no: the robot file has no unimouse.imu; the logs' gyro_z_rad_s is not used");
  }
  std::printf("\n%-28s %-20s %10s %12s %10s %12s\n", "log", "channel", "r2 before", "RMSE before",
              "r2 after", "RMSE after");
  for (const fit::ChannelFit& c : report.channels) {
    std::printf("%-28s %-20s %10.4f %12.4g %10.4f %12.4g\n", c.log.c_str(), c.channel.c_str(),
                c.r2_before, c.rmse_before, c.r2_after, c.rmse_after);
  }

  std::string logs;
  for (const fit::SysidLog& log : l.logs) {
    logs += (logs.empty() ? "" : ", ") + std::filesystem::path(log.file).filename().string();
  }
  const std::string patched =
      fit::PatchRobotText(ReadTextFile(l.robot_file), l.robot, report.parameters,
                          "fitted by `unimouse fit` to " + logs);
  // the written file must read back as a robot file with the fitted values
  const RobotSpec check = ParseRobotSpec(patched, l.robot_file + " (fitted)");
  for (const fit::FittedParameter& p : report.parameters) {
    const double back = fit::ParameterValue(check, p.ref);
    if (std::abs(back - p.value) > 1e-5 * std::abs(p.value)) {
      throw RuntimeFault("the fitted file does not read back " + Name(p.ref));
    }
  }
  std::filesystem::create_directories(o.out_dir);
  const std::string out =
      o.out_dir + "/" + std::filesystem::path(l.robot_file).stem().string() + "-fitted.yaml";
  WriteTextFile(out, patched);
  std::printf("\nwrote %s\n", out.c_str());
  const PlotNames plot_names(o.out_dir, l.logs);
  for (const fit::ChannelFit& c : report.channels) {
    const std::string plot = plot_names(c.log_index, c.channel, "fit");
    fit::WritePlot(plot, fit::FitPlot(c));
    std::printf("wrote %s\n", plot.c_str());
  }
  return kExitPassed;
}

int CompareCommand(const FitOptions& o) {
  const Loaded l = Load(o);
  PluginRegistry registry;
  registry.AddSearchPath(PluginSearchPath(o.plugin_path));
  struct Compared {
    size_t log_index;
    fit::ChannelComparison channel;
  };
  std::vector<Compared> compared;
  for (size_t i = 0; i < l.logs.size(); ++i) {
    const fit::SysidLog& log = l.logs[i];
    std::printf("%s replayed on %s\n", log.file.c_str(), l.robot_file.c_str());
    std::printf("%-20s %10s %12s %12s %10s\n", "channel", "RMSE", "max error", "at time_s", "r2");
    for (fit::ChannelComparison& c : fit::CompareLog(l.robot, registry, log)) {
      std::printf("%-20s %10.4g %12.4g %12.3f %10.4f\n", c.channel.c_str(), c.rmse, c.max_error,
                  c.max_error_time_s, c.r2);
      compared.push_back({i, std::move(c)});
    }
  }
  std::filesystem::create_directories(o.out_dir);
  const PlotNames plot_names(o.out_dir, l.logs);
  for (const Compared& c : compared) {
    const std::string plot = plot_names(c.log_index, c.channel.channel, "compare");
    fit::WritePlot(plot, fit::ComparePlot(l.logs[c.log_index].file, c.channel));
    std::printf("wrote %s\n", plot.c_str());
  }
  return kExitPassed;
}

void AddFitCommands(CommandLine& cli) {
  auto fit = std::make_shared<FitOptions>();
  CLI::App* fit_cmd = cli.app().add_subcommand(
      "fit",
      "fit a robot file's motor constants, and its gyro's bias and scale, to a robot's sysid logs "
      "(docs/calibrate.md)");
  fit_cmd->add_option("robot", fit->robot, "robot YAML file, or the name of a bundled robot")
      ->required();
  fit_cmd->add_option("logs", fit->logs, "CSV logs of the sysid test pattern")->required();
  fit_cmd->add_option("--out", fit->out_dir, "directory for the fitted robot file and the plots")
      ->capture_default_str();
  cli.Add(fit_cmd, [&cli, fit] {
    fit->plugin_path = cli.plugin_path();
    return FitCommand(*fit);
  });
  auto compare = std::make_shared<FitOptions>();
  CLI::App* compare_cmd = cli.app().add_subcommand(
      "compare", "replay a robot's sysid log on a robot file and say how far apart they are");
  compare_cmd->add_option("robot", compare->robot, "robot YAML file, or a bundled robot")
      ->required();
  compare_cmd->add_option("logs", compare->logs, "CSV logs of the sysid test pattern")->required();
  compare->out_dir = "compare";
  compare_cmd->add_option("--out", compare->out_dir, "directory for the plots")
      ->capture_default_str();
  cli.Add(compare_cmd, [&cli, compare] {
    compare->plugin_path = cli.plugin_path();
    return CompareCommand(*compare);
  });
}

}  // namespace unimouse
