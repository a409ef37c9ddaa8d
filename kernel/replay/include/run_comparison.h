// SPDX-License-Identifier: GPL-3.0-or-later
// Two runs side by side (`unimouse replay A B`): where one robot's path first leaves the other's.
#ifndef UNIMOUSE_REPLAY_RUN_COMPARISON_H_
#define UNIMOUSE_REPLAY_RUN_COMPARISON_H_

#include <optional>

#include "recording.h"

namespace unimouse {

/// How far apart two robots' positions on the floor must be for their runs to have diverged.
inline constexpr double kDivergence_m = 0.01;

struct Divergence {
  double t_s = 0;
  double distance_m = 0;  ///< between the two positions then
  Pose2D a, b;
};

/// The first of `a`'s sample times, within the time both paths cover, at which `b`'s position
/// (PoseAt) is more than `threshold_m` from `a`'s; none when they stay together.
std::optional<Divergence> FirstDivergence(const RecordedRobot& a, const RecordedRobot& b,
                                          double threshold_m = kDivergence_m);

}  // namespace unimouse

#endif  // UNIMOUSE_REPLAY_RUN_COMPARISON_H_
