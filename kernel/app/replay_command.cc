// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iterator>

#include "command_line.h"
#include "imported_run.h"
#include "install_paths.h"
#include "page_data.h"
#include "plugin_registry.h"
#include "recording.h"
#include "replay_page.h"
#include "replay_scene.h"
#include "replay_viewer.h"
#include "run_comparison.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

void Describe(const Recording& r) {
  std::printf("%s: %.3f s, %zu robot(s), %zu events, %zu log lines", r.path.c_str(), r.end_s,
              r.robots.size(), r.events.size(), r.log.size());
  const auto status = r.run_metadata.find("status");
  if (status != r.run_metadata.end()) std::printf(", the run %s", status->second.c_str());
  std::printf("\n");
  if (!r.cut_short.empty()) {
    std::printf("  warning: the recording was cut short (%s); it plays up to %.3f s\n",
                r.cut_short.c_str(), r.end_s);
  }
}

void SayDivergence(const std::string& what, const std::optional<Divergence>& d,
                   const RecordedRobot& a, const RecordedRobot& b) {
  if (!d) {
    const double both_s = std::min(a.poses.back().t_s, b.poses.back().t_s);
    std::printf("%s never diverge by more than %.0f cm over the %.3f s both cover\n", what.c_str(),
                kDivergence_m * 100, both_s);
    return;
  }
  std::printf("%s first diverge at %.3f s: %.1f cm apart, (%.3f, %.3f) m against (%.3f, %.3f) m\n",
              what.c_str(), d->t_s, d->distance_m * 100, d->a.x_m, d->a.y_m, d->b.x_m, d->b.y_m);
}

}  // namespace

void AddReplayCommand(CommandLine& cli) {
  auto options = std::make_shared<ReplayOptions>();
  CLI::App* replay = cli.app().add_subcommand(
      "replay",
      "play a run's recording (run.mcap) in a window or as one offline page, beside another run "
      "(docs/replay.md)");
  replay->add_option("recording", options->recordings, "a run.mcap, or the output folder of a run")
      ->required()
      ->expected(1, 2);
  replay->add_option("--import", options->import_csv,
                     "a real robot's logged run (CSV: time_s,x_m,y_m,yaw_rad or "
                     "time_s,left_counts,right_counts), drawn as a ghost");
  replay->add_option("--html", options->html,
                     "write the replay as one offline HTML page here instead of opening a window");
  replay->add_option("--signal", options->signals,
                     "a signal the page plots or the window's HUD shows (repeat for more; the "
                     "page's default: the motors, encoders and ToF sensors)");
  replay->add_option("--at", options->at_s, "start at this time, in seconds")
      ->check(CLI::NonNegativeNumber);
  replay
      ->add_option("--speed", options->speed,
                   "sim seconds per wall second: 0.1 0.25 0.5 1 2 4 8 16")
      ->check(
          CLI::IsMember(std::vector<double>(std::begin(kReplaySpeeds), std::end(kReplaySpeeds))));
  replay->add_flag("--paused", options->paused, "start paused");
  replay
      ->add_option("--view-frames", options->view_frames,
                   "close the window after this many frames, saving the last as replay.png")
      ->check(CLI::NonNegativeNumber);
  replay->add_option("--out", options->out_dir,
                     "where screenshots go (default: the first recording's folder)");
  cli.Add(replay, [options, &cli] {
    options->plugin_path = cli.plugin_path();
    return ReplayCommand(*options);
  });
}

int ReplayCommand(const ReplayOptions& o) {
  // everything is read and checked before anything is written or opened
  std::vector<Recording> recordings;
  for (const std::string& path : o.recordings) {
    recordings.push_back(ReadRecording(path));
    Describe(recordings.back());
  }
  const Recording& main = recordings.front();
  std::vector<RecordedRobot> ghosts;
  std::optional<Divergence> divergence;
  if (recordings.size() == 2) {
    for (RecordedRobot robot : recordings[1].robots) {
      robot.name = "B" + (robot.name.empty() ? "" : ": " + robot.name);
      ghosts.push_back(std::move(robot));
    }
    divergence = FirstDivergence(main.robots.front(), recordings[1].robots.front());
    SayDivergence("the runs", divergence, main.robots.front(), recordings[1].robots.front());
  }
  if (!o.import_csv.empty()) {
    std::optional<RobotSpec> spec;
    const auto file = main.attachments.find(main.robots.front().file);
    if (file != main.attachments.end()) spec = ParseRobotSpec(file->second, file->first);
    RecordedRobot logged = ReadImportedRun(o.import_csv, spec ? &*spec : nullptr,
                                           main.robots.front().poses.front().value);
    std::printf("%s: a logged run of %zu rows over %.3f s\n", o.import_csv.c_str(),
                logged.poses.size(), logged.poses.back().t_s - logged.poses.front().t_s);
    const std::optional<Divergence> apart = FirstDivergence(main.robots.front(), logged);
    SayDivergence("the simulation and the logged run", apart, main.robots.front(), logged);
    if (!divergence) divergence = apart;
    ghosts.push_back(std::move(logged));
  }

  if (!o.html.empty()) {
    WriteReplayPage(ReplayPageData(main, ghosts, o.signals, divergence), o.html);
    std::printf("page: %s\n", o.html.c_str());
    return kExitPassed;
  }
  PluginRegistry registry;
  registry.AddSearchPath(PluginSearchPath(o.plugin_path));
  ReplayScene scene(main, ghosts, registry);
  ReplayViewOptions view;
  view.title = "unimouse replay: " + main.path;
  view.start_s = std::min(o.at_s, main.end_s);
  view.paused = o.paused;
  view.speed = o.speed;
  view.max_frames = o.view_frames;
  view.out_dir = o.out_dir.empty() ? fs::path(main.path).parent_path().string() : o.out_dir;
  view.signals = o.signals;
  (void)scene.Hud(o.signals);  // a signal the recording has not is said before a window opens
  if (view.out_dir.empty()) view.out_dir = ".";
  ShowReplay(scene, view);
  return kExitPassed;
}

}  // namespace unimouse
