// SPDX-License-Identifier: GPL-3.0-or-later
#include "commands.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "firmware_beliefs.h"
#include "install_paths.h"
#include "kernel.h"
#include "maze_explorer.h"
#include "maze_plot.h"
#include "real_time_pacer.h"
#include "run_pictures.h"
#include "scenario.h"
#include "text_file.h"
#include "unimouse/errors.h"
#include "unimouse/plugin_abi.h"
#include "viewer.h"

namespace unimouse {
namespace {

PluginRegistry LoadRegistry(const std::string& plugin_path) {
  PluginRegistry registry;
  registry.AddSearchPath(PluginSearchPath(plugin_path));
  return registry;
}

std::unique_ptr<Maze> LoadMazeOption(const std::string& maze) {
  if (maze == "none") return nullptr;
  return std::make_unique<Maze>(LoadMaze(ResolveDataFile(maze, "mazes/", ".txt")));
}

void WriteResult(const std::string& out_dir, const nlohmann::json& result) {
  std::filesystem::create_directories(out_dir);
  WriteTextFile((std::filesystem::path(out_dir) / "result.json").string(), result.dump(2) + "\n");
}

// the maze as the firmware reported it on its debug channels: cells it knows (with their true
// walls dark), cells it visited, the path it last planned
void DrawFirmwareBeliefs(const Maze& maze, const FirmwareBeliefs& beliefs,
                         const std::string& out_dir) {
  WallKnowledge knowledge(maze);
  auto sense = [&](Cell c) {
    if (maze.Contains(c)) knowledge.Sense(maze, c);
  };
  for (const auto& [cell, walls] : beliefs.walls) sense({cell.first, cell.second});
  for (const Cell& c : beliefs.visited) sense(c);
  MazePicture picture;
  picture.maze = &maze;
  picture.knowledge = &knowledge;
  picture.closed_path = DescribeRoute(beliefs.path, maze.start_heading());
  const std::filesystem::path base = std::filesystem::path(out_dir) / "maze";
  WriteMazePicture(picture, base.string() + ".png");
  WriteMazePicture(picture, base.string() + ".svg");
  std::printf("  maze as the firmware saw it: %s.png\n", base.string().c_str());
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

// the pictures asked for; without any, final.png whenever the machine can draw
std::unique_ptr<RunPictures> MakePictures(Kernel& kernel, const RobotSpec& robot,
                                          const PictureOptions& asked,
                                          const FirmwareBeliefs* beliefs,
                                          const RunOptions& options) {
  if (asked.Any() || options.no_pictures) {
    return std::make_unique<RunPictures>(kernel, asked, beliefs, options.out_dir);
  }
  PictureOptions final_only = asked;
  final_only.at_end = true;
  try {
    return std::make_unique<RunPictures>(kernel, final_only, beliefs, options.out_dir);
  } catch (const RenderUnavailable& e) {
    std::printf("  no pictures: %s\n", e.what());
    return std::make_unique<RunPictures>(kernel, asked, beliefs, options.out_dir);
  }
}

// one run, headless or in the viewer's window
int RunOnce(const RunOptions& options, Viewer* viewer) {
  UNIMOUSE_THROW_UNLESS(options.duration_s > 0 && std::isfinite(options.duration_s),
                        "--duration must be a positive number of seconds");
  const std::string robot_file = ResolveDataFile(options.robot, "robots/", ".yaml");
  RobotSpec robot = LoadRobotSpec(robot_file);
  if (!options.link.empty()) {
    // the firmware drives the robot's inputs through the link, added as the last component; the
    // transport itself says whether it runs in lock-step from the first step
    const std::string params = "{transport: '" + options.link + "'}";
    robot.components.push_back(
        {"unimouse.link", "link", std::nullopt, ParseYaml(params, "--link"), {"--link", 1, 1}});
  }
  // a scenario builds its own world
  std::unique_ptr<Scenario> scenario;
  std::string scenario_file;
  std::unique_ptr<Maze> maze;
  ScenarioWorld scenario_world;
  double duration_s = options.duration_s;
  if (!options.scenario.empty()) {
    std::map<std::string, std::string> overrides;
    for (const auto& set : options.sets) {
      const size_t eq = set.find('=');
      UNIMOUSE_THROW_UNLESS(eq != std::string::npos && eq > 0,
                            "--set " + set + ": write name=value");
      overrides[set.substr(0, eq)] = set.substr(eq + 1);
    }
    scenario_file = ResolveDataFile(options.scenario, "scenarios/", ".lua");
    scenario = Scenario::Load(scenario_file, overrides, options.seed);
    scenario_world = scenario->BuildWorld();
    maze = std::move(scenario_world.maze);
    // a second beyond the limit lets the scenario give its own reason
    if (!options.duration_given && scenario->time_limit_s() > 0) {
      duration_s = scenario->time_limit_s() + 1;
    }
  } else {
    UNIMOUSE_THROW_UNLESS(options.sets.empty() && options.controller.empty(),
                          "--set and --controller go with --scenario");
    maze = LoadMazeOption(options.maze);
  }
  const PluginRegistry registry = LoadRegistry(options.plugin_path);
  std::filesystem::create_directories(options.out_dir);

  // every message goes to the console with its sim time and into the run's log, line by line
  const std::string log_path = (std::filesystem::path(options.out_dir) / "log.txt").string();
  std::shared_ptr<std::FILE> log(std::fopen(log_path.c_str(), "w"), [](std::FILE* f) {
    if (f) std::fclose(f);
  });
  UNIMOUSE_THROW_UNLESS(log != nullptr, log_path + ": cannot write the run's log");
  KernelOptions kernel_options;
  kernel_options.seed = options.seed;
  kernel_options.output_dir = options.out_dir;
  kernel_options.boxes = std::move(scenario_world.boxes);
  kernel_options.spawn = scenario_world.spawn;
  kernel_options.log_sink = [log](double time_s, int level, const std::string& component,
                                  const std::string& message) {
    const char* kind = level == UNIMOUSE_LOG_ERROR     ? "error: "
                       : level == UNIMOUSE_LOG_WARNING ? "warning: "
                                                       : "";
    std::fprintf(stderr, "[%9.3f s] %s: %s%s\n", time_s, component.c_str(), kind, message.c_str());
    std::fprintf(log.get(), "%.6f\t%s\t%s%s\n", time_s, component.c_str(), kind, message.c_str());
    std::fflush(log.get());
  };
  std::unique_ptr<Kernel> kernel = Kernel::Create(robot, maze.get(), registry, kernel_options);

  nlohmann::json result;
  if (scenario) scenario->Attach(*kernel, options.controller);
  UNIMOUSE_THROW_UNLESS(options.snapshot_on.empty() || scenario,
                        "--snapshot-on watches a scenario's events: give --scenario");
  const PictureOptions asked = PicturesFor(options);
  // what the firmware reports on the link's debug channels, for the pictures and the maze plot
  FirmwareBeliefs beliefs;
  kernel->AddReportListener(
      [&beliefs](const std::string&, const unimouse_report& report) { beliefs.Apply(report); });
  std::unique_ptr<RunPictures> pictures = MakePictures(*kernel, robot, asked, &beliefs, options);
  if (scenario) {
    pictures->SetHudSource([&scenario] { return scenario->hud(); });
    scenario->SetPictureTaker(
        [&pictures](const std::string& file, const std::string& camera, int width, int height) {
          return pictures->Save(file, camera, width, height);
        });
    for (const auto& kind : options.snapshot_on) {
      scenario->SnapshotOn(kind, asked.camera, asked.width, asked.height);
    }
  }
  result["robot"] = robot_file;
  result["maze"] = maze && !scenario
                       ? nlohmann::json(ResolveDataFile(options.maze, "mazes/", ".txt"))
                       : nlohmann::json(nullptr);
  result["seed"] = options.seed;
  result["duration_s"] = duration_s;

  const int64_t steps = std::llround(duration_s / kernel->timestep_s());
  // a viewer paces the run itself, to its own speed
  const bool pace = viewer == nullptr && (options.realtime || !options.link.empty());
  RealTimePacer pacer(kernel->timestep_s());
  const auto start = std::chrono::steady_clock::now();
  auto over = [&] { return kernel->state().step() >= steps || (scenario && scenario->finished()); };
  auto step = [&] {
    kernel->Step();
    pictures->AfterStep();
  };
  std::string fault;
  try {
    if (viewer != nullptr) {
      Viewer::Run shown{kernel.get(), &robot, &beliefs, step, over, nullptr, nullptr};
      if (scenario) {
        shown.hud = [&scenario] { return scenario->hud(); };
        shown.verdict = [&scenario] {
          const ScenarioOutcome& o = scenario->outcome();
          return o.status + (o.reason.empty() ? "" : ": " + o.reason);
        };
      }
      viewer->Show(shown);
    }
    while (viewer == nullptr && !over()) {
      step();
      // hardware runs on the wall clock; firmware in lock-step sets the pace itself
      if (pace && !kernel->firmware_paced()) pacer.Wait(kernel->state().step());
    }
    if (scenario) scenario->Finish();
  } catch (const RuntimeFault& e) {
    fault = e.what();
  }
  pictures->Finish();
  kernel->Finish();
  if (maze && !options.link.empty()) DrawFirmwareBeliefs(*maze, beliefs, options.out_dir);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // the run's record is written whatever happened to the run
  const mjData& d = kernel->state().data();
  const Pose2D pose = kernel->world().RobotPose(d);
  result["status"] = fault.empty() ? "completed" : "fault";
  if (!fault.empty()) result["error"] = fault;
  result["sim_time_s"] = d.time;
  result["steps"] = kernel->state().step();
  result["wall_time_s"] = wall_s;
  result["real_time_factor"] = wall_s > 0 ? d.time / wall_s : 0.0;
  result["robot_pose"] = {{"x_m", pose.x_m}, {"y_m", pose.y_m}, {"yaw_rad", pose.yaw_rad}};
  result["collision_proxy_overflows"] = kernel->world().proxy_overflows();
  if (scenario) {
    ScenarioOutcome outcome = scenario->outcome();
    if (outcome.status == "running" && fault.empty()) {
      outcome.status = "failed";
      outcome.reason = "not decided when the run ended at " + std::to_string(d.time) + " s";
    }
    result["scenario"] = {{"name", scenario->name()},     {"file", scenario_file},
                          {"params", scenario->params()}, {"status", outcome.status},
                          {"reason", outcome.reason},     {"scores", outcome.scores},
                          {"hud", scenario->hud()}};
    if (!scenario->traceback().empty()) result["scenario"]["traceback"] = scenario->traceback();
  }
  if (pace) result["real_time_pacing"] = pacer.Report();
  if (viewer != nullptr) result["view"] = {{"frames", viewer->frames()}};
  if (pictures->written() > 0) {
    result["pictures"] = {{"written", pictures->written()}, {"renderer", pictures->renderer()}};
  }
  WriteResult(options.out_dir, result);

  const std::string where = scenario ? "in scenario " + scenario->name()
                            : maze
                                ? "in maze " + options.maze + " (" + std::to_string(maze->width()) +
                                      "x" + std::to_string(maze->height()) + ")"
                                : std::string("on an open floor");
  std::printf("unimouse run: robot '%s' %s, seed %llu\n", robot.name.c_str(), where.c_str(),
              static_cast<unsigned long long>(options.seed));
  std::printf("  simulated %.3f s in %lld steps, %.2f s wall time, %.0fx real time\n", d.time,
              static_cast<long long>(kernel->state().step()), wall_s,
              result["real_time_factor"].get<double>());
  std::printf("  robot at (%.3f, %.3f) m heading %.1f deg\n", pose.x_m, pose.y_m,
              pose.yaw_rad * 180 / std::numbers::pi);
  if (pictures->written() > 0) {
    std::printf("  %d picture%s in %s (%s)\n", pictures->written(),
                pictures->written() == 1 ? "" : "s", options.out_dir.c_str(),
                pictures->renderer().c_str());
  }
  std::printf("  result: %s\n",
              (std::filesystem::path(options.out_dir) / "result.json").string().c_str());
  if (!fault.empty()) {
    std::fprintf(stderr, "unimouse: error: %s\n", fault.c_str());
    return kExitRuntimeFault;
  }
  if (scenario) {
    const std::string status = result["scenario"]["status"];
    std::printf("  scenario %s: %s%s%s\n", scenario->name().c_str(), status.c_str(),
                result["scenario"]["reason"].get<std::string>().empty() ? "" : ": ",
                result["scenario"]["reason"].get<std::string>().c_str());
    return status == "passed" ? kExitPassed : kExitFailed;
  }
  return kExitPassed;
}

}  // namespace

int RunCommand(const RunOptions& options) {
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
  // checking opens no port, starts no firmware and makes no link outside the scratch directory
  kernel_options.start_components = false;
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
  kernel.reset();
  std::filesystem::remove_all(scratch);
  return kExitPassed;
}

int PluginsCommand(const std::string& plugin_path) {
  std::cout << DescribePlugins(LoadRegistry(plugin_path));
  return kExitPassed;
}

}  // namespace unimouse
