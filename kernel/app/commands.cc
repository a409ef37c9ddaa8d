// SPDX-License-Identifier: GPL-3.0-or-later
#include "commands.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string_view>
#include <utility>

#include "command_line.h"
#include "geom_extent.h"
#include "install_paths.h"
#include "kernel.h"
#include "plugin_registry.h"
#include "scenario.h"
#include "session.h"
#include "transport_spec.h"
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
  p.required = !options.session.snapshot_on.empty();
  return p;
}

// one run, headless or in the viewer's window
int RunOnce(const RunOptions& options, Viewer* viewer) {
  SessionOptions o = options.session;
  o.paced_by_caller = viewer != nullptr;
  // a line that rewrites itself is for a person at a terminal, never for a pipe or a file
  o.progress = viewer == nullptr && ::isatty(STDERR_FILENO) == 1;
  try {
    if (!options.bad_options.empty()) throw InputError(options.bad_options);
    o.pictures = PicturesFor(options);
  } catch (const InputError& e) {
    // a run that could not start says so where its result would be
    WriteErrorResult(o, e.what(), kExitBadInput);
    throw;
  }
  std::unique_ptr<Session> session = Session::Open(o);

  std::optional<ViewRecord> view;
  if (viewer != nullptr) {
    // the window steps the run at its own speed; closing it ends the run
    viewer->Show(*session);
    view = ViewRecord{viewer->frames(), viewer->FramesPerSecond()};
  } else {
    while (!session->Over()) session->Step();
  }
  const RunRecord r = session->Finish(view);

  const std::string out_dir = options.session.out_dir;
  if (r.firmware_maze) {
    std::printf("  maze as the firmware saw it: %s\n",
                (std::filesystem::path(out_dir) / "maze.png").string().c_str());
  }
  std::printf("unimouse run: robot '%s' %s, seed %llu\n", session->robot().name.c_str(),
              session->where().c_str(), static_cast<unsigned long long>(options.session.seed));
  std::printf("  simulated %.3f s in %lld steps, %.2f s wall time, %.0fx real time\n", r.sim_time_s,
              static_cast<long long>(r.steps), r.wall_time_s, r.real_time_factor);
  if (r.firmware_paced) {
    // in lock-step the firmware's time is part of every step: say where the time went
    const TickTimes& split = r.wall_time_split;
    std::printf(
        "  wall time: physics %.2f s, components %.2f s, firmware %.2f s, scenario %.2f s\n",
        split.physics_s, split.components_s, split.firmware_s, split.scenario_s);
  }
  const Pose2D& pose = r.robot().pose;
  std::printf("  robot at (%.3f, %.3f) m heading %.1f deg\n", pose.x_m, pose.y_m,
              pose.yaw_rad * 180 / std::numbers::pi);
  if (r.view) {
    std::printf("  viewer: %lld frames, %.1f a second\n", static_cast<long long>(r.view->frames),
                r.view->frames_per_second);
  }
  if (!r.pictures_unavailable.empty()) {
    std::printf("  no pictures: %s\n", r.pictures_unavailable.c_str());
  } else if (r.pictures_written > 0) {
    std::printf("  %d picture%s in %s (%s)\n", r.pictures_written,
                r.pictures_written == 1 ? "" : "s", out_dir.c_str(), r.pictures_renderer.c_str());
  }
  std::printf("  result: %s\n", (std::filesystem::path(out_dir) / "result.json").string().c_str());
  if (!r.error.empty()) {
    std::fprintf(stderr, "unimouse: error: %s\n", r.error.c_str());
  } else if (r.scenario) {
    const ScenarioOutcome& outcome = r.scenario->outcome;
    std::printf("  scenario %s: %s%s%s\n", r.scenario->name.c_str(), outcome.status.c_str(),
                outcome.reason.empty() ? "" : ": ", outcome.reason.c_str());
  }
  return r.exit_code;
}

}  // namespace

int RunCommand(const RunOptions& options) {
  InstallInterruptHandlers();
  if (!options.view) return RunOnce(options, nullptr);
  const std::string& scenario = options.session.scenario;
  const std::string what = scenario.empty() ? "run" : "scenario " + scenario;
  Viewer viewer("unimouse: " + what, options.session.out_dir, options.view_frames);
  for (;;) {
    const int code = RunOnce(options, &viewer);
    if (!viewer.restart_requested()) return code;
    std::printf("unimouse run: starting again\n");
  }
}

namespace {

// a kernel built as a run would build it, with no component started: no port, program or file
// is opened, so the scratch directory it is given is never made
std::unique_ptr<Kernel> CheckedKernel(const RobotSpec& robot, const Maze* maze,
                                      const PluginRegistry& registry, KernelOptions options) {
  options.output_dir =
      (std::filesystem::temp_directory_path() / ("unimouse-check-" + std::to_string(::getpid())))
          .string();
  options.start_components = false;
  return Kernel::Create(robot, maze, registry, options);
}

// a robot as built, at rest at its spawn pose: the wheels on the floor, and something else
// (a caster) touching it too, or it tips over onto its chassis once the run starts
void WarnIfItCannotStand(const mjModel& m, const mjData& d) {
  constexpr double kTouch_m = 0.001;
  std::map<int, double> lowest_of_body;  // the robot's bodies that touch things
  for (int g = 0; g < m.ngeom; ++g) {
    const int body = m.geom_bodyid[g];
    if (body == 0 || (m.geom_contype[g] == 0 && m.geom_conaffinity[g] == 0)) continue;
    if (!HasReach(m, g)) continue;
    constexpr double kUp[3] = {0, 0, 1};
    const double z = d.geom_xpos[3 * g + 2] - GeomReach(m, d, g, kUp);
    const auto [at, fresh] = lowest_of_body.emplace(body, z);
    if (!fresh) at->second = std::min(at->second, z);
  }
  if (lowest_of_body.empty()) return;
  double floor_z = lowest_of_body.begin()->second;
  for (const auto& [body, z] : lowest_of_body) floor_z = std::min(floor_z, z);
  bool wheel_touches = false, other_touches = false;
  for (const auto& [body, z] : lowest_of_body) {
    const char* name = mj_id2name(&m, mjOBJ_BODY, body);
    // a wheel turns on a hinge that a motor drives
    bool wheel = false;
    for (int a = 0; a < m.nu; ++a) {
      wheel = wheel || (m.actuator_trntype[a] == mjTRN_JOINT &&
                        m.jnt_bodyid[m.actuator_trnid[2 * a]] == body);
    }
    const bool touches = z - floor_z <= kTouch_m;
    (wheel ? wheel_touches : other_touches) |= touches;
    if (wheel && !touches) {
      std::printf(
          "  warning: wheel '%s' is %.1f mm above the floor at rest: it does not touch it\n", name,
          (z - floor_z) * 1000);
    }
  }
  if (wheel_touches && !other_touches) {
    for (const auto& [body, z] : lowest_of_body) {
      const int parent = m.body_parentid[body];
      if (parent == 0 || m.body_jntnum[body] == 0) continue;
      bool wheel = false;
      for (int a = 0; a < m.nu; ++a) {
        wheel = wheel || m.jnt_bodyid[m.actuator_trnid[2 * a]] == body;
      }
      if (wheel) continue;
      std::printf(
          "  warning: '%s' is %.1f mm above the floor at rest: only the wheels touch it, so the "
          "robot tips onto its chassis as it starts\n",
          mj_id2name(&m, mjOBJ_BODY, body), (z - floor_z) * 1000);
    }
  }
}

void CheckRobot(const std::string& robot_name, const PluginRegistry& registry) {
  const std::string robot_file = ResolveDataFile(robot_name, "robots/", ".yaml");
  const RobotSpec robot = LoadRobotSpec(robot_file);
  const std::unique_ptr<Kernel> kernel = CheckedKernel(robot, nullptr, registry, {});
  const mjModel& m = kernel->mj_model();
  std::printf("%s: ok: robot '%s', %d bodies, %d joints, %d actuators, %zu components\n",
              robot_file.c_str(), robot.name.c_str(), m.nbody - 1, m.njnt, m.nu,
              kernel->model().components.size());
  WarnIfItCannotStand(m, kernel->state().data());
  const Model& model = kernel->model();
  for (const EarlyRead& e : model.early_reads) {
    std::printf(
        "  note: '%s' reads signal '%s' before '%s' writes it, so within a phase it sees "
        "the previous tick's value\n",
        model.components[e.reader].name.c_str(), model.signal_names[e.signal].c_str(),
        model.components[e.writer].name.c_str());
  }
}

// loads the scenario and builds its world around the bundled robot, as a run would before its
// first step
void CheckScenario(const std::string& name, const std::map<std::string, std::string>& overrides,
                   const PluginRegistry& registry) {
  const std::string file = ResolveDataFile(name, "scenarios/", ".lua");
  const std::unique_ptr<Scenario> scenario = Scenario::Load(file, overrides, 1);
  ScenarioWorld world = scenario->BuildWorld();
  const RobotSpec robot = LoadRobotSpec(ResolveDataFile("unimouse", "robots/", ".yaml"));
  KernelOptions options;
  options.spawn = world.spawn;
  options.boxes = world.boxes;
  CheckedKernel(robot, world.maze.get(), registry, options);
  const std::string floor = world.maze ? "maze " + world.maze_file + " (" +
                                             std::to_string(world.maze->width()) + "x" +
                                             std::to_string(world.maze->height()) + ")"
                                       : std::string("an open floor");
  std::printf("%s: ok: scenario '%s', %zu parameters, world: %s, walls and boxes: %zu\n",
              file.c_str(), scenario->name().c_str(), scenario->params().size(), floor.c_str(),
              world.boxes.size());
}

// what `check` is given, a directory standing for every robot file and scenario inside it
std::vector<std::string> CheckTargets(const std::vector<std::string>& targets) {
  std::vector<std::string> files;
  for (const std::string& target : targets) {
    if (!std::filesystem::is_directory(target)) {
      files.push_back(target);
      continue;
    }
    std::vector<std::string> inside;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(target)) {
      const std::string extension = entry.path().extension().string();
      if (entry.is_regular_file() &&
          (extension == ".yaml" || extension == ".yml" || extension == ".lua")) {
        inside.push_back(entry.path().string());
      }
    }
    // sorted, so that two checks of one directory report alike
    std::sort(inside.begin(), inside.end());
    if (inside.empty())
      throw InputError(target + ": no robot file (.yaml) or scenario (.lua) in it");
    files.insert(files.end(), inside.begin(), inside.end());
  }
  return files;
}

// a scenario: a .lua file, or the name of a bundled scenario that no bundled robot shares
bool IsScenario(const std::string& target) {
  if (std::filesystem::path(target).extension() == ".lua") return true;
  const std::filesystem::path data = DataDirectory();
  return target.find('/') == std::string::npos && !std::filesystem::exists(target) &&
         !std::filesystem::exists(data / "robots" / (target + ".yaml")) &&
         std::filesystem::exists(data / "scenarios" / (target + ".lua"));
}

}  // namespace

int CheckCommand(const CheckOptions& options) {
  const std::map<std::string, std::string> overrides = Scenario::ParseOverrides(options.sets);
  const PluginRegistry registry = LoadRegistry(options.plugin_path);
  int worst = kExitPassed;
  for (const std::string& target : CheckTargets(options.targets)) {
    // each is reported, and a problem in one does not hide the others
    int code = kExitPassed;
    try {
      if (IsScenario(target)) {
        // a .lua file that returns a function is a controller, as a class submits them
        const std::string file = ResolveDataFile(target, "scenarios/", ".lua");
        if (Scenario::ReturnsFunction(file)) {
          std::printf("%s: ok: controller, returns function(time_s)\n", file.c_str());
        } else {
          CheckScenario(target, overrides, registry);
        }
      } else {
        CheckRobot(target, registry);
      }
    } catch (const InputError& e) {
      std::fprintf(stderr, "unimouse: error: %s\n", e.what());
      code = kExitBadInput;
    } catch (const RuntimeFault& e) {
      // a script error in a file being checked: the file is the bad input
      std::fprintf(stderr, "unimouse: error: %s\n", e.what());
      code = kExitBadInput;
    }
    worst = std::max(worst, code);
  }
  return worst;
}

int PluginsCommand(const std::string& plugin_path) {
  std::cout << DescribePlugins(LoadRegistry(plugin_path));
  return kExitPassed;
}

namespace {

// a table cell: a '|' of its own would end it
std::string Cell(const std::string& text) {
  std::string cell;
  for (char c : text) cell += c == '|' ? std::string("\\|") : std::string(1, c);
  return cell;
}

// each part of a robot file as docs/robots.md titles it
constexpr std::pair<const char*, const char*> kRobotParts[] = {
    {"robot", "the file's top level"},
    {"body", "the chassis and every body under it"},
    {"moving body", "every body but the chassis, besides the body keys"},
    {"joint", "a body's joint"},
    {"geom", "an entry of a body's geoms"},
    {"site", "an entry of a body's sites"},
    {"actuator", "an entry of actuators"},
    {"component", "an entry of components"},
};

std::string RobotSchemaMarkdown(const PluginRegistry& registry) {
  std::ostringstream out;
  out << "### The robot file\n\n";
  for (const auto& [part, title] : kRobotParts) {
    out << "#### " << part << ": " << title << "\n\n"
        << "| key | type | unit | default | range | meaning |\n|---|---|---|---|---|---|\n";
    for (const RobotKey& k : RobotKeys()) {
      if (std::string_view(k.part) != part) continue;
      out << "| `" << k.key << "` | " << k.type << " | " << UnitOfName(k.key) << " | "
          << k.default_text << " | " << Cell(k.range) << " | " << k.meaning << " |\n";
    }
    out << "\n";
  }
  out << "### Component types\n\nThe `params` of each component type found.\n\n";
  for (const auto& [name, entry] : registry.entries()) {
    const unimouse_component_type& t = *entry.type;
    out << "#### `" << name << "`\n\n"
        << (t.summary ? t.summary : "") << ". Runs "
        << (t.default_period_s > 0 ? "every " + ParamNumberText(t.default_period_s) + " s"
                                   : std::string("every step"))
        << " unless `period_s` is given.\n\n"
        << "| parameter | kind | unit | default | range | meaning |\n"
        << "|---|---|---|---|---|---|\n";
    for (int i = 0; i < t.nparam; ++i) {
      const unimouse_param& p = t.params[i];
      out << "| `" << p.name << "` | " << ParamKindName(p.kind) << " | " << UnitOfName(p.name)
          << " | " << Cell(ParamDefaultText(p)) << " | " << Cell(ParamRangeText(p)) << " | "
          << Cell(p.doc ? p.doc : "") << " |\n";
    }
    out << "\n";
  }
  std::string text = out.str();
  text.pop_back();  // no blank line before the block's end
  return text;
}

}  // namespace

int RobotSchemaCommand(bool markdown, const std::string& plugin_path) {
  const PluginRegistry registry = LoadRegistry(plugin_path);
  if (markdown) {
    std::cout << RobotSchemaMarkdown(registry);
    return kExitPassed;
  }
  for (const RobotKey& k : RobotKeys()) {
    std::cout << k.part << ": " << k.key << " (" << k.type << "), " << k.default_text
              << (*k.range ? ", " + std::string(k.range) : "") << ": " << k.meaning << "\n";
  }
  std::cout << DescribePlugins(registry);
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

namespace {

// the link plugin's own words for its transports (its `transport` parameter), so that this help
// lists exactly the transports the installed link has
std::string LinkHelp() {
  const std::string fallback = "connect firmware (`unimouse plugins` lists the transports)";
  try {
    PluginRegistry registry;
    registry.AddSearchPath(PluginSearchPath(""));
    const PluginRegistry::Entry* link = registry.Find("unimouse.link");
    for (int i = 0; link != nullptr && i < link->type->nparam; ++i) {
      const unimouse_param& p = link->type->params[i];
      if (std::string(p.name) == "transport" && p.doc != nullptr) {
        return std::string("connect firmware: ") + p.doc;
      }
    }
  } catch (const std::exception&) {
    // a broken plugin is reported when a command loads it, not in the help
  }
  return fallback;
}

// `unimouse run --robot A [--link X] --robot B [--controller c.lua] ...`: with several robots
// each robot's options are those after its --robot; with one, they may come anywhere, once
// each. Returns why they cannot be read, or "".
std::string GroupRobotOptions(const CLI::App& run_cmd, RunOptions& run) {
  const char* const own[] = {"--link",       "--link-set", "--firmware-profile",
                             "--controller", "--start",    "--name"};
  const auto value = [&](const char* option, size_t i) {
    return run_cmd.get_option(option)->as<std::vector<std::string>>().at(i);
  };
  if (run_cmd.get_option("--robot")->count() < 2) {
    for (const char* option : own) {
      if (run_cmd.get_option(option)->count() > 1 && std::string(option) != "--link-set") {
        return std::string(option) + " is given twice for one robot";
      }
    }
    const auto one = [&](const char* option, std::string& into) {
      if (run_cmd.get_option(option)->count() == 1) into = value(option, 0);
    };
    one("--robot", run.session.robot);
    one("--link", run.session.link);
    one("--firmware-profile", run.session.firmware_profile);
    one("--controller", run.session.controller);
    one("--start", run.session.start);
    if (run_cmd.get_option("--name")->count() > 0) {
      return "--name tells robots apart: it goes with two or more --robot";
    }
    return "";
  }
  std::map<const CLI::Option*, size_t> seen;
  for (const CLI::Option* option : run_cmd.parse_order()) {
    const std::string name = option->get_name();
    const std::string text = value(name.c_str(), seen[option]++);
    if (name == "--robot") {
      run.session.robots.push_back({});
      run.session.robots.back().robot = text;
      continue;
    }
    if (std::find(std::begin(own), std::end(own), name) == std::end(own)) continue;
    if (run.session.robots.empty()) {
      return name + " " + text +
             " comes before the first --robot: with several robots, each robot's options "
             "follow its --robot";
    }
    SessionRobot& robot = run.session.robots.back();
    std::string* single = name == "--link"               ? &robot.link
                          : name == "--firmware-profile" ? &robot.firmware_profile
                          : name == "--controller"       ? &robot.controller
                          : name == "--start"            ? &robot.start
                          : name == "--name"             ? &robot.name
                                                         : nullptr;
    if (single == nullptr) {
      robot.link_sets.push_back(text);
    } else if (!single->empty()) {
      return name + " is given twice for robot " + robot.robot;
    } else {
      *single = text;
    }
  }
  return "";
}

}  // namespace

void AddRunCommand(CommandLine& cli) {
  auto run = std::make_shared<RunOptions>();
  // several robots: each --robot starts a robot, and the options for one robot after it are its
  // own; GroupRobotOptions reads them in order from the options themselves
  const auto every = CLI::MultiOptionPolicy::TakeAll;
  CLI::App* run_cmd =
      cli.app().add_subcommand("run", "run a simulation headless and write a result");
  run_cmd
      ->add_option("--robot",
                   "robot YAML file, or the name of a bundled robot (default unimouse); give "
                   "it again for each robot of a run with several, each followed by its own "
                   "--link, --link-set, --firmware-profile, --controller, --start and --name")
      ->multi_option_policy(every);
  run_cmd->add_option("--maze", run->session.maze, "maze file, a bundled maze's name, or none")
      ->capture_default_str();
  run_cmd->add_option("--duration", run->session.duration_s, "simulated seconds")
      ->capture_default_str();
  run_cmd->add_option("--seed", run->session.seed, "seed of every random stream")
      ->capture_default_str()
      // an unsigned parse would take -1 as 18446744073709551615
      ->check([](const std::string& text) {
        return text.find_first_not_of("0123456789") == std::string::npos
                   ? std::string()
                   : "the seed is a whole number, 0 or more";
      });
  run_cmd->add_option("--out", run->session.out_dir, "directory for result.json and other outputs")
      ->capture_default_str();
  run_cmd->add_option("--scenario", run->session.scenario,
                      "challenge to run: a scenario file, the name of a bundled one, or none "
                      "for the robot alone (without --scenario, --set, --controller and --link "
                      "the run is the contest driven by the bundled firmware)");
  run_cmd->add_option("--set", run->session.sets, "scenario parameter, name=value (repeatable)");
  run_cmd
      ->add_option("--controller",
                   "Lua file returning function(time_s) that drives the robot through sim.*")
      ->multi_option_policy(every);
  run_cmd
      ->add_option("--start",
                   "the robot's start: a cell and a heading, X,Y,H (H one of N, E, S, W), "
                   "e.g. 15,15,S")
      ->multi_option_policy(every);
  run_cmd
      ->add_option("--name",
                   "the robot's name among several (default: its file's name, then -2, -3)")
      ->multi_option_policy(every);
  run_cmd->add_flag("-v,--verbose", run->session.verbose,
                    "the console shows detail too: the firmware's reports of walls, cells, "
                    "paths and values (log.txt always has them)");
  run_cmd->add_flag("--realtime", run->session.realtime,
                    "pace the simulation to the wall clock, even a firmware in lock-step, to "
                    "watch it (a board or a program on a link, from --link or the robot file, "
                    "is paced anyway until it turns lock-step on)");
  const std::string link_help = LinkHelp();
  run_cmd->add_option("--link", link_help)->multi_option_policy(every);
  run_cmd->add_option("--link-set", run->session.link_sets,
                      "a link parameter, name=value, as `unimouse plugins` lists them for "
                      "unimouse.link (repeatable), e.g. --link-set failsafe_s=0");
  run_cmd
      ->add_option("--firmware-profile",
                   "what the firmware expects: unimouse (this project's library, the "
                   "default) or unimousesim-0.1 (built against the original UnimouseSim's "
                   "library: 1.0 m ToF scale, commands held while silent, no extensions)")
      ->multi_option_policy(every);

  run_cmd->add_option("--trace-period", run->session.trace.period_s,
                      "seconds between the rows of the trace (trace.csv, the robot file's "
                      "unimouse.logger, every 10 ms in the bundled robot); 0 for no trace");
  run_cmd->add_option("--trace-signals", run->session.trace.signals,
                      "the signals the trace records, comma-separated, instead of the robot "
                      "file's list");
  run_cmd
      ->add_option("--record", run->session.record,
                   "the recording, run.mcap (docs/replay.md): light (poses and signals at "
                   "100 Hz, the log, the maze), full (every step) or off")
      ->capture_default_str();

  // pictures: none of these changes what is run
  run_cmd->add_option("--camera", run->camera, "camera of the pictures: top, chase or free")
      ->capture_default_str();
  run_cmd->add_option("--snapshot-size", run->snapshot_size, "size of the pictures, WIDTHxHEIGHT")
      ->capture_default_str();
  run_cmd->add_option("--snapshot-every", run->snapshot_every,
                      "a picture every so much sim time (1s, 250ms): snapshots/<time>s.png");
  run_cmd->add_option("--snapshot-at", run->snapshot_at,
                      "a picture at this sim time, e.g. 12.5 (repeatable)");
  run_cmd->add_option("--snapshot-on", run->session.snapshot_on,
                      "a picture at each scenario event: cell_entered, wall_contact, "
                      "gate_crossed, firmware_log (repeatable): events/<event>_<n>.png");
  run_cmd->add_flag("--snapshot-end", run->snapshot_end,
                    "final.png when the run ends, or exit 2 if the machine cannot draw (without "
                    "this flag final.png is taken whenever the machine can)");
  run_cmd->add_flag("--no-pictures", run->session.only_asked_pictures, "not even final.png");
  run_cmd->add_option("--frames-fps", run->frames_fps,
                      "frames/NNNNNN.png at this many frames per sim second");
  run_cmd->add_option("--video", run->video, "an MP4 of the run in the output directory (ffmpeg)");
  run_cmd->add_option("--video-fps", run->video_fps, "frames per sim second of the video")
      ->capture_default_str();
  run_cmd->add_flag("--view", run->view,
                    "watch in a live 3D window: orbit, zoom, pause, step, speed, follow (press H)");
  run_cmd->add_option("--view-frames", run->view_frames,
                      "close the window after so many frames, saving the last as view.png");

  cli.Add(run_cmd, [&cli, run_cmd, run] {
    run->session.plugin_path = cli.plugin_path();
    run->session.duration_given = run_cmd->get_option("--duration")->count() > 0;
    run->session.maze_given = run_cmd->get_option("--maze")->count() > 0;
    run->bad_options = GroupRobotOptions(*run_cmd, *run);
    // the main job: no challenge and no driver chosen, so the contest with the bundled racer
    // firmware; the robot, the maze, the duration, the seed, the pacing and the
    // pictures change how it runs, not what runs. An open floor has no contest, and
    // `--scenario none` asks for the robot alone
    bool chosen = run->session.maze == "none";
    for (const char* option : {"--scenario", "--set", "--controller", "--link"}) {
      chosen = chosen || run_cmd->get_option(option)->count() > 0;
    }
    if (run->session.scenario == "none") run->session.scenario.clear();
    if (!chosen) {
      run->session.scenario = "micromouse";
      run->session.sets = {"end_on_log=done"};
      run->session.link =
          link::BundledFirmwareSpec(link::FirmwareHost::kInProcess, FirmwareDirectory(), "racer");
      for (SessionRobot& robot : run->session.robots) robot.link = run->session.link;
    }
    return RunCommand(*run);
  });
}

void AddCheckCommand(CommandLine& cli) {
  auto check = std::make_shared<CheckOptions>();
  CLI::App* check_cmd =
      cli.app().add_subcommand("check", "validate robot files and scenarios without running them");
  check_cmd
      ->add_option("files", check->targets,
                   "robot YAML files, scenario or controller .lua files, bundled robot or "
                   "scenario names, or directories (every .yaml and .lua inside). A robot's "
                   "components are created and bound; a scenario is loaded and its world built "
                   "around the bundled robot; a controller (a file that returns a function) is "
                   "loaded. Nothing is started or written. Each is reported; the exit code is the "
                   "worst")
      ->required();
  check_cmd->add_option("--set", check->sets,
                        "scenario parameter, name=value (repeatable), as `run --set` takes it");

  cli.Add(check_cmd, [&cli, check] {
    check->plugin_path = cli.plugin_path();
    return CheckCommand(*check);
  });
}

void AddInformationCommands(CommandLine& cli) {
  CLI::App* plugins_cmd =
      cli.app().add_subcommand("plugins", "list the component types found and their parameters");

  auto schema_markdown = std::make_shared<bool>(false);
  CLI::App* schema_cmd = cli.app().add_subcommand(
      "robot-schema", "list every key a robot file may give and every component's parameters");
  schema_cmd->add_flag("--markdown", *schema_markdown,
                       "print the reference of docs/robots.md instead");

  CLI::App* api_cmd =
      cli.app().add_subcommand("scenario-api", "list the sim.* functions scenarios can call");

  auto scenarios_markdown = std::make_shared<bool>(false);
  CLI::App* scenarios_cmd = cli.app().add_subcommand(
      "scenarios", "list the bundled scenarios and the parameters --set can change");
  scenarios_cmd->add_flag("--markdown", *scenarios_markdown,
                          "print the table of docs/scenarios.md instead");

  cli.Add(plugins_cmd, [&cli] { return PluginsCommand(cli.plugin_path()); });
  cli.Add(schema_cmd, [&cli, schema_markdown] {
    return RobotSchemaCommand(*schema_markdown, cli.plugin_path());
  });
  cli.Add(scenarios_cmd, [scenarios_markdown] { return ScenariosCommand(*scenarios_markdown); });
  cli.Add(api_cmd, [] {
    std::fputs(DescribeScenarioApi().c_str(), stdout);
    return kExitPassed;
  });
}

}  // namespace unimouse
