// SPDX-License-Identifier: GPL-3.0-or-later
// The calibration plots: lines land on the pixels that the documented layout (residual_plot.h)
// puts their values at, computed here by hand; the PNG reads back at its stated size.
#include "residual_plot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fit.h"
#include "png_file.h"
#include "run_program.h"

namespace unimouse::fit {
namespace {

Rgb8 PixelAt(const std::vector<uint8_t>& rgb, int x, int y) {
  const size_t at = (static_cast<size_t>(y) * kPlotWidth_px + static_cast<size_t>(x)) * 3;
  return {rgb[at], rgb[at + 1], rgb[at + 2]};
}

// the rows of column x within [y0, y1] that have colour c
std::vector<int> RowsOf(const std::vector<uint8_t>& rgb, int x, int y0, int y1, Rgb8 c) {
  std::vector<int> rows;
  for (int y = y0; y <= y1; ++y) {
    if (PixelAt(rgb, x, y) == c) rows.push_back(y);
  }
  return rows;
}

// 0 to 10 s every 10 ms; above, a ramp 0 to 100 (black) and a constant 30 (blue); below, two
// constants -2 (orange) and 2 (blue)
Plot RampPlot() {
  Plot plot;
  plot.title = "ramp";
  PlotLine ramp{{}, kLoggedColour}, flat{{}, kFittedColour};
  PlotLine minus{{}, kFileColour}, plus{{}, kFittedColour};
  for (int i = 0; i <= 1000; ++i) {
    plot.time_s.push_back(i * 0.01);
    ramp.values.push_back(i * 0.1);
    flat.values.push_back(30);
    minus.values.push_back(-2);
    plus.values.push_back(2);
  }
  plot.panels.push_back({"values", {ramp, flat}});
  plot.panels.push_back({"residual", {minus, plus}});
  return plot;
}

TEST(ResidualPlotTest, DrawsEachLineWhereItsValuesAre) {
  const std::vector<uint8_t> rgb = RenderPlot(RampPlot());
  ASSERT_EQ(rgb.size(), static_cast<size_t>(kPlotWidth_px) * kPlotHeight_px * 3);
  const PanelBox top = PlotPanelBox(0, 2);
  // the top panel spans 0..100 and 5 % more each way: -5 at its bottom row, 105 at its top
  const auto top_y = [&](double v) {
    return top.y1 - static_cast<int>(std::lround((v + 5) / 110 * (top.y1 - top.y0)));
  };
  for (double t : {1.0, 2.5, 5.0, 7.5, 9.0}) {
    SCOPED_TRACE(t);
    const int x = top.x0 + static_cast<int>(std::lround(t / 10 * (top.x1 - top.x0)));
    // the ramp's value at t is 10 t; one pixel either way for the line's neighbouring samples
    const std::vector<int> ramp = RowsOf(rgb, x, top.y0, top.y1, kLoggedColour);
    ASSERT_FALSE(ramp.empty());
    EXPECT_LE(std::abs(ramp.front() - top_y(10 * t)), 1);
    EXPECT_LE(std::abs(ramp.back() - top_y(10 * t)), 1);
    EXPECT_EQ(RowsOf(rgb, x, top.y0, top.y1, kFittedColour), std::vector<int>{top_y(30)});
  }

  const PanelBox bottom = PlotPanelBox(1, 2);
  EXPECT_GT(bottom.y0, top.y1);
  // -2..2 and 5 % more: -2.2 at the bottom row, 2.2 at the top; the zero between them
  const auto bottom_y = [&](double v) {
    return bottom.y1 - static_cast<int>(std::lround((v + 2.2) / 4.4 * (bottom.y1 - bottom.y0)));
  };
  const int x = (bottom.x0 + bottom.x1) / 2;
  EXPECT_EQ(RowsOf(rgb, x, bottom.y0, bottom.y1, kFileColour), std::vector<int>{bottom_y(-2)});
  EXPECT_EQ(RowsOf(rgb, x, bottom.y0, bottom.y1, kFittedColour), std::vector<int>{bottom_y(2)});
  EXPECT_EQ(RowsOf(rgb, x, bottom.y0, bottom.y1, kZeroColour), std::vector<int>{bottom_y(0)});
}

TEST(ResidualPlotTest, WritesAPngOfTheStatedSizeThatReadsBackAsDrawn) {
  const std::string path = testing::FreshDirectory("residual_plot") + "/ramp.png";
  WritePlot(path, RampPlot());
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(path, &width, &height);
  EXPECT_EQ(width, 960);
  EXPECT_EQ(height, 540);
  EXPECT_EQ(rgb, RenderPlot(RampPlot()));
}

TEST(ResidualPlotTest, AFitsResidualsAreTheReplayLessTheLog) {
  ChannelFit c;
  c.log = "/some/where/log.csv";
  c.channel = "left_counts_per_s";
  c.time_s = {0.01, 0.02, 0.03};
  c.logged = {1, 2, 3};
  c.replayed_before = {2, 2, 2};
  c.replayed_after = {1, 2, 3.5};
  const Plot plot = FitPlot(c);
  EXPECT_EQ(plot.time_s, c.time_s);
  ASSERT_EQ(plot.panels.size(), 2u);
  ASSERT_EQ(plot.panels[0].lines.size(), 3u);
  EXPECT_EQ(plot.panels[0].lines[0].values, c.logged);
  ASSERT_EQ(plot.panels[1].lines.size(), 2u);
  EXPECT_EQ(plot.panels[1].lines[0].values, (std::vector<double>{1, 0, -1}));
  EXPECT_EQ(plot.panels[1].lines[1].values, (std::vector<double>{0, 0, 0.5}));
  EXPECT_EQ(plot.title.find("/some/where"), std::string::npos);
}

TEST(PlotStemsTest, GiveEachLogItsOwnNameAlsoForTheSameLogTwiceOrOneNameInTwoFolders) {
  const std::vector<std::string> stems =
      PlotStems({"a/sysid.csv", "a/sysid.csv", "b/sysid.csv", "sysid-2.csv", "run.log"});
  EXPECT_EQ(stems, (std::vector<std::string>{"sysid", "sysid-2", "sysid-3", "sysid-2-2", "run"}));
}

}  // namespace
}  // namespace unimouse::fit
