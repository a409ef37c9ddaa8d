// SPDX-License-Identifier: GPL-3.0-or-later
// Pages as a reader sees them: Debian's `chromium` headless loads a file, runs its scripts, and
// gives back the rendered DOM (--dump-dom) or a screenshot. Shared by the browser tests of the
// batch report and the replay page.
#ifndef UNIMOUSE_TESTS_HEADLESS_CHROMIUM_H_
#define UNIMOUSE_TESTS_HEADLESS_CHROMIUM_H_

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "run_program.h"

namespace unimouse::testing {

/// The path of `program` in a directory of PATH, or "" when none has it.
std::string FindProgram(const std::string& program);

/// Chromium headless in a 1200 x 1000 window at one device pixel per CSS pixel, without scroll
/// bars, with its profile and caches in a directory of the test's own.
class HeadlessChromium {
 public:
  /// `program` is chromium's path (FindProgram("chromium")).
  HeadlessChromium(std::string program, std::filesystem::path profile_dir)
      : program_(std::move(program)), profile_dir_(std::move(profile_dir)) {}

  /// Runs chromium with `options` (e.g. "--dump-dom") on `address`; its stderr is dropped.
  Outcome Run(const std::string& options, const std::string& address) const;

  /// The DOM of the page at `address` after its scripts ran (expects chromium to exit with 0).
  std::string Dom(const std::string& address) const;

 private:
  std::string program_;
  std::filesystem::path profile_dir_;
};

/// The value of attribute `name` in the first tag of `dom` that starts with `tag_start`, or ""
/// when there is none.
std::string AttributeOf(const std::string& dom, const std::string& tag_start,
                        const std::string& name);

/// AttributeOf as a number; NaN, and a failed expectation, when the attribute is missing.
double NumberAttribute(const std::string& dom, const std::string& tag_start,
                       const std::string& name);

/// The pixels of one colour in a screenshot: how many, their centroid (pixel centres, in page
/// pixels) and the direction of their longer axis on screen (radians, y down, modulo pi).
struct Blob {
  double count = 0, x = 0, y = 0, axis = 0;
};

/// The pixels of `rgb` (width x height, 3 bytes a pixel) within 4 of (r, g, b) in each channel.
Blob FindColour(const std::vector<uint8_t>& rgb, int width, int height, int r, int g, int b);

/// Robot 0 of a replay page as a screenshot shows it, placed in the world through the scene's
/// mapping that the same page gives in its DOM (kernel/report/replay_page/replay.js).
struct ShownRobot {
  double x_m = 0, y_m = 0;
  double yaw_rad = 0;       ///< its long axis, known modulo pi
  Blob blob;                ///< its pixels, in the robot's colour #e6007e
  double pixels_per_m = 0;  ///< the scene's scale
  std::string dom;          ///< the DOM the mapping was read from
};

/// Opens the replay page at `address` (with its #t=... fragment) twice, for its DOM and for a
/// screenshot written to `screenshot`, and finds robot 0 on the screenshot.
ShownRobot RobotOnScreen(const HeadlessChromium& chromium, const std::string& address,
                         const std::filesystem::path& screenshot);

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_HEADLESS_CHROMIUM_H_
