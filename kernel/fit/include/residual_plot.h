// SPDX-License-Identifier: GPL-3.0-or-later
// The pictures `unimouse fit` and `unimouse compare` write beside their report
// (docs/calibrate.md, "Worked example"): one channel of one log against time, in panels stacked one
// above the other that share the time axis, drawn pixel by pixel and written as PNG.
#ifndef UNIMOUSE_FIT_RESIDUAL_PLOT_H_
#define UNIMOUSE_FIT_RESIDUAL_PLOT_H_

#include <cstdint>
#include <string>
#include <vector>

#include "firmware_beliefs.h"

namespace unimouse::fit {

/// Size of every plot, pixels.
inline constexpr int kPlotWidth_px = 960, kPlotHeight_px = 540;

/// The colours of the plots' lines: the log, the replay with the file's values, the replay with
/// the fitted (or compared) values, and the zero of a residual panel.
inline constexpr Rgb8 kLoggedColour{0, 0, 0};
inline constexpr Rgb8 kFileColour{255, 140, 0};
inline constexpr Rgb8 kFittedColour{31, 95, 214};
inline constexpr Rgb8 kZeroColour{160, 160, 160};

struct PlotLine {
  std::vector<double> values;  ///< one per time
  Rgb8 colour;
};

struct PlotPanel {
  std::string label;  ///< drawn at the panel's top left
  std::vector<PlotLine> lines;
};

struct Plot {
  std::string title;           ///< drawn above the panels
  std::vector<double> time_s;  ///< increasing; the x axis
  std::vector<PlotPanel> panels;
};

/// Where panel `index` of `panels` plots, pixels, inclusive: time_s.front() at x0 and
/// time_s.back() at x1; the panel's smallest value less 5 % of its lines' span at y1 and its
/// largest plus 5 % at y0 (y grows downwards). A panel whose lines do not vary spans the value
/// +-1.
struct PanelBox {
  int x0, y0, x1, y1;
};
PanelBox PlotPanelBox(int index, int panels);

/// Draws the plot as 8-bit RGB rows, top first, kPlotWidth_px by kPlotHeight_px: white, each
/// panel's frame, its lines joined point to point in their order (the last on top), and the
/// title, label and each panel's top and bottom values in the bitmap font.
std::vector<uint8_t> RenderPlot(const Plot& plot);

/// The start of each log's plot names, in the order of `log_files`: the file name without its
/// extension, followed by -2, -3, ... where an earlier log already took it (the same log given
/// twice, two logs of one name in different folders), so that no two logs share one.
std::vector<std::string> PlotStems(const std::vector<std::string>& log_files);

/// Renders the plot and writes it as a PNG; throws InputError when it cannot be written.
void WritePlot(const std::string& path, const Plot& plot);

}  // namespace unimouse::fit

#endif  // UNIMOUSE_FIT_RESIDUAL_PLOT_H_
