// SPDX-License-Identifier: GPL-3.0-or-later
#include "commands.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "install_paths.h"
#include "kernel.h"
#include "scenario.h"
#include "session.h"
#include "unimouse/errors.h"
#include "viewer.h"

namespace unimouse {
namespace {

PluginRegistry LoadRegistry(const std::string& plugin_path) {
  PluginRegistry registry;
  registry.AddSearchPath(PluginSearchPath(plugin_path));
  return registry;
}

// "1.5", "1.5s" or "250ms" as seconds
double ParseSeconds(const std::string& text, const char* option) {
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  const std::string unit = end;
  if (unit == "ms") v /= 1000;
  UNIMOUSE_THROW_UNLESS(
      end != text.c_str() && (unit.empty() || unit == "s" || unit == "ms") && std::isfinite(v) &&
          v >= 0,
      std::string(option) + " " + text + ": write seconds, like 1.5, 1.5s or 250ms");
  return v;
}

PictureOptions PicturesFor(const RunOptions& options) {
  PictureOptions p;
  p.camera = options.camera;
  char x = 0;
  char rest = 0;
  UNIMOUSE_THROW_UNLESS(
      std::sscanf(options.snapshot_size.c_str(), "%d%c%d%c", &p.width, &x, &p.height, &rest) == 3 &&
          x == 'x',
      "--snapshot-size " + options.snapshot_size + ": write WIDTHxHEIGHT");
  if (!options.snapshot_every.empty()) {
    p.every_s = ParseSeconds(options.snapshot_every, "--snapshot-every");
    UNIMOUSE_THROW_UNLESS(p.every_s > 0, "--snapshot-every must be more than 0 s");
  }
  for (const auto& t : options.snapshot_at) p.at_s.push_back(ParseSeconds(t, "--snapshot-at"));
  p.at_end = options.snapshot_end;
  p.frames_fps = options.frames_fps;
  p.video = options.video;
  p.video_fps = options.video_fps;
  p.required = !options.snapshot_on.empty();
  return p;
}

// one run, headless or in the viewer's window
int RunOnce(const RunOptions& options, Viewer* viewer) {
  SessionOptions o;
  o.robot = options.robot;
  o.maze = options.maze;
  o.duration_s = options.duration_s;
  o.duration_given = options.duration_given;
  o.maze_given = options.maze_given;
  o.seed = options.seed;
  o.out_dir = options.out_dir;
  o.plugin_path = options.plugin_path;
  o.link = options.link;
  o.link_sets = options.link_sets;
  o.firmware_profile = options.firmware_profile;
  o.realtime = options.realtime;
  o.paced_by_caller = viewer != nullptr;
  o.scenario = options.scenario;
  o.sets = options.sets;
  o.controller = options.controller;
  o.snapshot_on = options.snapshot_on;
  o.only_asked_pictures = options.no_pictures;
  try {
    o.pictures = PicturesFor(options);
  } catch (const InputError& e) {
    // a run that could not start says so where its result would be
    WriteErrorResult(o, e.what(), kExitBadInput);
    throw;
  }
  std::unique_ptr<Session> session = Session::Open(o);

  nlohmann::json extra;
  if (viewer != nullptr) {
    // the window steps the run at its own speed; closing it ends the run
    viewer->Show(*session);
    extra["view"] = {{"frames", viewer->frames()}};
  } else {
    while (!session->Over()) session->Step();
  }
  const SessionResult result = session->Finish(extra);
  const nlohmann::json& r = result.record;

  const std::string out_dir = options.out_dir;
  if (r.contains("firmware_maze")) {
    std::printf("  maze as the firmware saw it: %s\n",
                (std::filesystem::path(out_dir) / "maze.png").string().c_str());
  }
  std::printf("unimouse run: robot '%s' %s, seed %llu\n", session->robot().name.c_str(),
              session->where().c_str(), static_cast<unsigned long long>(options.seed));
  std::printf("  simulated %.3f s in %lld steps, %.2f s wall time, %.0fx real time\n",
              r["sim_time_s"].get<double>(), r["steps"].get<long long>(),
              r["wall_time_s"].get<double>(), r["real_time_factor"].get<double>());
  if (r["firmware_paced"].get<bool>()) {
    // in lock-step the firmware's time is part of every step: say where the time went
    const auto& split = r["wall_time_split_s"];
    std::printf(
        "  wall time: physics %.2f s, components %.2f s, firmware %.2f s, scenario %.2f s\n",
        split["physics"].get<double>(), split["components"].get<double>(),
        split["firmware"].get<double>(), split["scenario"].get<double>());
  }
  const auto& pose = r["robot_pose"];
  std::printf("  robot at (%.3f, %.3f) m heading %.1f deg\n", pose["x_m"].get<double>(),
              pose["y_m"].get<double>(), pose["yaw_rad"].get<double>() * 180 / std::numbers::pi);
  if (r.contains("pictures") && r["pictures"].contains("unavailable")) {
    std::printf("  no pictures: %s\n", r["pictures"]["unavailable"].get<std::string>().c_str());
  } else if (r.contains("pictures")) {
    const int written = r["pictures"]["written"];
    std::printf("  %d picture%s in %s (%s)\n", written, written == 1 ? "" : "s", out_dir.c_str(),
                r["pictures"]["renderer"].get<std::string>().c_str());
  }
  std::printf("  result: %s\n", (std::filesystem::path(out_dir) / "result.json").string().c_str());
  if (r.contains("error")) {
    std::fprintf(stderr, "unimouse: error: %s\n", r["error"].get<std::string>().c_str());
  } else if (r.contains("scenario")) {
    const std::string status = r["scenario"]["status"];
    const std::string reason = r["scenario"]["reason"];
    std::printf("  scenario %s: %s%s%s\n", r["scenario"]["name"].get<std::string>().c_str(),
                status.c_str(), reason.empty() ? "" : ": ", reason.c_str());
  }
  return result.exit_code;
}

}  // namespace

int RunCommand(const RunOptions& options) {
  InstallInterruptHandlers();
  if (!options.view) return RunOnce(options, nullptr);
  const std::string what = options.scenario.empty() ? "run" : "scenario " + options.scenario;
  Viewer viewer("unimouse: " + what, options.out_dir, options.view_frames);
  for (;;) {
    const int code = RunOnce(options, &viewer);
    if (!viewer.restart_requested()) return code;
    std::printf("unimouse run: starting again\n");
  }
}

int CheckCommand(const std::string& robot_name, const std::string& plugin_path) {
  const std::string robot_file = ResolveDataFile(robot_name, "robots/", ".yaml");
  const RobotSpec robot = LoadRobotSpec(robot_file);
  const PluginRegistry registry = LoadRegistry(plugin_path);
  // components are really created and bound; whatever files they open go somewhere harmless
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("unimouse-check-" + std::to_string(::getpid()));
  KernelOptions kernel_options;
  kernel_options.output_dir = scratch.string();
  kernel_options.start_components = false;  // no port, program or file is opened
  std::unique_ptr<Kernel> kernel;
  try {
    kernel = Kernel::Create(robot, nullptr, registry, kernel_options);
  } catch (...) {
    std::filesystem::remove_all(scratch);
    throw;
  }
  const mjModel& m = kernel->mj_model();
  std::printf("%s: ok: robot '%s', %d bodies, %d joints, %d actuators, %zu components\n",
              robot_file.c_str(), robot.name.c_str(), m.nbody - 1, m.njnt, m.nu,
              kernel->model().components.size());
  const Model& model = kernel->model();
  for (const EarlyRead& e : model.early_reads) {
    std::printf(
        "  note: '%s' reads signal '%s' before '%s' writes it, so within a phase it sees "
        "the previous tick's value\n",
        model.components[e.reader].name.c_str(), model.signal_names[e.signal].c_str(),
        model.components[e.writer].name.c_str());
  }
  kernel.reset();
  std::filesystem::remove_all(scratch);
  return kExitPassed;
}

int PluginsCommand(const std::string& plugin_path) {
  std::cout << DescribePlugins(LoadRegistry(plugin_path));
  return kExitPassed;
}

int ScenariosCommand(bool markdown) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(DataDirectory() + "/scenarios")) {
    if (entry.path().extension() == ".lua") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (markdown) std::cout << "| scenario | parameter | type | default |\n|---|---|---|---|\n";
  for (const auto& file : files) {
    // loading runs only the file's top level: no world is built and nothing is written
    const auto scenario = Scenario::Load(file.string(), {}, 1);
    if (!markdown) std::cout << scenario->name() << " (" << file.string() << ")\n";
    for (const auto& [name, value] : scenario->params()) {
      const std::string& type = scenario->param_types().at(name);
      const std::string shown = type == "string" ? "\"" + value + "\"" : value;
      if (markdown) {
        std::cout << "| `" << scenario->name() << "` | `" << name << "` | " << type << " | `"
                  << shown << "` |\n";
      } else {
        std::cout << "  " << name << " = " << shown << "  (" << type << ")\n";
      }
    }
  }
  return kExitPassed;
}

}  // namespace unimouse
