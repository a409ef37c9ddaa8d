// SPDX-License-Identifier: GPL-3.0-or-later
// The fitted robot file: the original text with only the fitted values changed, each component
// it changes preceded by a comment naming the logs and the fit.
#ifndef UNIMOUSE_FIT_ROBOT_PATCH_H_
#define UNIMOUSE_FIT_ROBOT_PATCH_H_

#include <string>
#include <vector>

#include "fit.h"
#include "robot_spec.h"

namespace unimouse::fit {

/// Returns `text` (the robot file `robot` was read from) with each identified parameter's value
/// written in place (or added to its component's params), and above each changed component a
/// comment: `provenance` and the values before and after.
std::string PatchRobotText(const std::string& text, const RobotSpec& robot,
                           const std::vector<FittedParameter>& parameters,
                           const std::string& provenance);

}  // namespace unimouse::fit

#endif  // UNIMOUSE_FIT_ROBOT_PATCH_H_
