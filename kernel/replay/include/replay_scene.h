// SPDX-License-Identifier: GPL-3.0-or-later
// A recording shown on the simulator's own model of its robots, for the replay viewer: the
// robots rebuilt from the robot files the recording carries, in its scenery, placed at the
// recorded poses of a chosen time with the recorded signals (so the ToF beams show), and beside
// them the firmware's beliefs and the HUD of that time. Nothing is simulated: no step is taken
// and no component is started.
#ifndef UNIMOUSE_REPLAY_REPLAY_SCENE_H_
#define UNIMOUSE_REPLAY_REPLAY_SCENE_H_

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "firmware_beliefs.h"
#include "kernel.h"
#include "plugin_registry.h"
#include "recording.h"

namespace unimouse {

class ReplayScene {
 public:
  /// Builds the recording's robots, and each ghost (another run's robot, a real robot's log) as a
  /// copy of the first robot drawn translucent. Throws InputError when the recording carries no
  /// robot file this unimouse can build.
  ReplayScene(const Recording& recording, std::vector<RecordedRobot> ghosts,
              const PluginRegistry& registry);

  /// Puts every robot where it was at `t_s` (clamped to the recording), with its signals then.
  void ShowAt(double t_s);
  double time_s() const { return time_s_; }
  /// The recording's last time.
  double end_s() const { return recording_.end_s; }
  /// The times of the first robot's samples.
  const std::vector<double>& sample_times() const { return sample_times_; }

  Kernel& kernel() { return *kernel_; }
  /// What the firmware believed at the time shown.
  const FirmwareBeliefs& beliefs() const { return beliefs_; }
  /// The scenario's HUD lines at the time shown, then the firmware's values then (one line), then
  /// each of `signals` (recorded names) with its value then. Throws InputError naming a signal
  /// the recording has not.
  std::vector<std::string> Hud(const std::vector<std::string>& signals = {}) const;
  /// The times a player jumps between: events, and log lines at info level or above.
  const std::vector<double>& marks() const { return marks_; }

 private:
  const Recording& recording_;
  std::vector<RecordedRobot> ghosts_;
  std::unique_ptr<Kernel> kernel_;
  std::vector<int> signal_column_;  // for each kernel signal, its column in the recording, or -1
  FirmwareBeliefs beliefs_;
  std::vector<double> marks_;
  std::vector<double> sample_times_;
  double time_s_ = -1;
  ptrdiff_t signal_row_ = -1;  // the recording's last signal row at or before time_s_
};

}  // namespace unimouse

#endif  // UNIMOUSE_REPLAY_REPLAY_SCENE_H_
