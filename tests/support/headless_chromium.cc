// SPDX-License-Identifier: GPL-3.0-or-later
#include "headless_chromium.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <system_error>

#include "png_file.h"

namespace unimouse::testing {

namespace fs = std::filesystem;

std::string FindProgram(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path == nullptr ? "" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((dir + "/" + program).c_str(), X_OK) == 0) {
      return dir + "/" + program;
    }
  }
  return "";
}

Outcome HeadlessChromium::Run(const std::string& options, const std::string& address) const {
  // --no-sandbox: the sandbox cannot start as root, and the pages are the tests' own files.
  // --hide-scrollbars: a screenshot would have a scroll bar that --dump-dom has not, and lay the
  // page out 15 px narrower
  const std::string profile = profile_dir_.string();
  return Shell("XDG_CONFIG_HOME=" + profile + " XDG_CACHE_HOME=" + profile + " " + program_ +
               " --headless --no-sandbox --disable-gpu --no-first-run "
               "--force-device-scale-factor=1 --window-size=1200,1000 --hide-scrollbars "
               "--user-data-dir=" +
               profile + " " + options + " '" + address + "' 2>/dev/null");
}

std::string HeadlessChromium::Dom(const std::string& address) const {
  const Outcome chromium = Run("--dump-dom", address);
  EXPECT_EQ(chromium.exit_code, 0);
  return chromium.output;
}

std::string AttributeOf(const std::string& dom, const std::string& tag_start,
                        const std::string& name) {
  const size_t tag = dom.find(tag_start);
  if (tag == std::string::npos) return "";
  const size_t end = dom.find('>', tag);
  const std::string marker = " " + name + "=\"";
  const size_t at = dom.find(marker, tag);
  if (at == std::string::npos || at > end) return "";
  const size_t start = at + marker.size();
  return dom.substr(start, dom.find('"', start) - start);
}

double NumberAttribute(const std::string& dom, const std::string& tag_start,
                       const std::string& name) {
  const std::string value = AttributeOf(dom, tag_start, name);
  EXPECT_FALSE(value.empty()) << tag_start << " has no " << name;
  return value.empty() ? NAN : std::stod(value);
}

Blob FindColour(const std::vector<uint8_t>& rgb, int width, int height, int r, int g, int b) {
  constexpr int kTolerance = 4;
  Blob blob;
  double sum_xx = 0, sum_yy = 0, sum_xy = 0;
  for (int row = 0; row < height; ++row) {
    for (int column = 0; column < width; ++column) {
      const uint8_t* pixel = &rgb[3 * (static_cast<size_t>(row) * width + column)];
      if (std::abs(pixel[0] - r) > kTolerance || std::abs(pixel[1] - g) > kTolerance ||
          std::abs(pixel[2] - b) > kTolerance) {
        continue;
      }
      const double x = column + 0.5, y = row + 0.5;
      blob.count += 1;
      blob.x += x;
      blob.y += y;
      sum_xx += x * x;
      sum_yy += y * y;
      sum_xy += x * y;
    }
  }
  if (blob.count == 0) return blob;
  blob.x /= blob.count;
  blob.y /= blob.count;
  const double mu20 = sum_xx / blob.count - blob.x * blob.x;
  const double mu02 = sum_yy / blob.count - blob.y * blob.y;
  const double mu11 = sum_xy / blob.count - blob.x * blob.y;
  blob.axis = 0.5 * std::atan2(2 * mu11, mu20 - mu02);
  return blob;
}

ShownRobot RobotOnScreen(const HeadlessChromium& chromium, const std::string& address,
                         const fs::path& screenshot) {
  ShownRobot shown;
  shown.dom = chromium.Dom(address);
  const std::string& dom = shown.dom;
  EXPECT_NE(dom.find("data-ready=\"1\""), std::string::npos) << dom;
  const std::string canvas = "<canvas id=\"scene\"";
  const double left = NumberAttribute(dom, canvas, "data-page-left");
  const double top = NumberAttribute(dom, canvas, "data-page-top");
  const double origin_x = NumberAttribute(dom, canvas, "data-origin-x");
  const double origin_y = NumberAttribute(dom, canvas, "data-origin-y");
  shown.pixels_per_m = NumberAttribute(dom, canvas, "data-px-per-m");

  // an old screenshot must not stand in for one chromium failed to write
  std::error_code ignored;
  fs::remove(screenshot, ignored);
  EXPECT_EQ(chromium.Run("--screenshot=" + screenshot.string(), address).exit_code, 0);
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(screenshot.string(), &width, &height);
  shown.blob = FindColour(rgb, width, height, 0xe6, 0x00, 0x7e);
  // on screen y grows downward: north is up
  shown.x_m = (shown.blob.x - left - origin_x) / shown.pixels_per_m;
  shown.y_m = (origin_y - (shown.blob.y - top)) / shown.pixels_per_m;
  shown.yaw_rad = -shown.blob.axis;
  return shown;
}

}  // namespace unimouse::testing
