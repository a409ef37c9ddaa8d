// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_comparison.h"

#include <cmath>

namespace unimouse {

std::optional<Divergence> FirstDivergence(const RecordedRobot& a, const RecordedRobot& b,
                                          double threshold_m) {
  if (a.poses.empty() || b.poses.empty()) return std::nullopt;
  const double end_s = std::min(a.poses.back().t_s, b.poses.back().t_s);
  for (const Timed<Pose2D>& at : a.poses) {
    if (at.t_s > end_s) break;
    if (at.t_s < b.poses.front().t_s) continue;
    const Pose2D other = PoseAt(b, at.t_s);
    const double distance = std::hypot(at.value.x_m - other.x_m, at.value.y_m - other.y_m);
    if (distance > threshold_m) return Divergence{at.t_s, distance, at.value, other};
  }
  return std::nullopt;
}

}  // namespace unimouse
