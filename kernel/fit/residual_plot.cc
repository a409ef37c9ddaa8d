// SPDX-License-Identifier: GPL-3.0-or-later
#include "residual_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "bitmap_font.h"
#include "png_file.h"

namespace unimouse::fit {
namespace {

// room for the values at the left, the title at the top, and between the panels
constexpr int kLeft_px = 80, kRight_px = 10, kTop_px = 24, kBottom_px = 14, kGap_px = 24;
constexpr Rgb8 kFrame{90, 90, 90};
constexpr Rgb8 kText{0, 0, 0};

class Canvas {
 public:
  Canvas() : rgb_(static_cast<size_t>(kPlotWidth_px) * kPlotHeight_px * 3, 255) {}

  void Set(int x, int y, Rgb8 c) {
    if (x < 0 || y < 0 || x >= kPlotWidth_px || y >= kPlotHeight_px) return;
    uint8_t* p = &rgb_[(static_cast<size_t>(y) * kPlotWidth_px + static_cast<size_t>(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }

  // Bresenham's line, both ends drawn
  void Line(int x0, int y0, int x1, int y1, Rgb8 c) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    for (int e = dx + dy;;) {
      Set(x0, y0, c);
      if (x0 == x1 && y0 == y1) return;
      const int e2 = 2 * e;
      if (e2 >= dy) e += dy, x0 += sx;
      if (e2 <= dx) e += dx, y0 += sy;
    }
  }

  // text in the 5 x 7 font, its top left at (x, y)
  void Text(const std::string& text, int x, int y, Rgb8 c) {
    for (char ch : text) {
      const Glyph& glyph = GlyphOf(ch);
      for (int gy = 0; gy < kGlyphHeight_px; ++gy) {
        for (int gx = 0; gx < kGlyphWidth_px; ++gx) {
          if (glyph[static_cast<size_t>(gy)] >> (kGlyphWidth_px - 1 - gx) & 1) {
            Set(x + gx, y + gy, c);
          }
        }
      }
      x += kGlyphWidth_px + 1;
    }
  }

  std::vector<uint8_t>& rgb() { return rgb_; }

 private:
  std::vector<uint8_t> rgb_;
};

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", v);
  return text;
}

}  // namespace

PanelBox PlotPanelBox(int index, int panels) {
  const int height = (kPlotHeight_px - kTop_px - kBottom_px - (panels - 1) * kGap_px) / panels;
  const int y0 = kTop_px + index * (height + kGap_px);
  return {kLeft_px, y0, kPlotWidth_px - 1 - kRight_px, y0 + height - 1};
}

std::vector<uint8_t> RenderPlot(const Plot& plot) {
  Canvas canvas;
  canvas.Text(plot.title, kLeft_px, (kTop_px - kGlyphHeight_px) / 2, kText);
  const int panels = static_cast<int>(plot.panels.size());
  const double t0 = plot.time_s.empty() ? 0 : plot.time_s.front();
  const double t1 = plot.time_s.empty() ? 1 : plot.time_s.back();
  for (int k = 0; k < panels; ++k) {
    const PlotPanel& panel = plot.panels[static_cast<size_t>(k)];
    const PanelBox box = PlotPanelBox(k, panels);
    double lo = INFINITY, hi = -INFINITY;
    for (const PlotLine& line : panel.lines) {
      for (double v : line.values) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (!(lo < hi)) {
      // a flat (or empty) panel: its value in the middle
      const double mid = std::isfinite(lo) ? lo : 0;
      lo = mid - 1, hi = mid + 1;
    } else {
      const double margin = 0.05 * (hi - lo);
      lo -= margin, hi += margin;
    }
    const auto x_of = [&](double t) {
      return box.x0 + static_cast<int>(std::lround((t - t0) / (t1 - t0) * (box.x1 - box.x0)));
    };
    const auto y_of = [&](double v) {
      return box.y1 - static_cast<int>(std::lround((v - lo) / (hi - lo) * (box.y1 - box.y0)));
    };
    canvas.Line(box.x0 - 1, box.y0 - 1, box.x1 + 1, box.y0 - 1, kFrame);
    canvas.Line(box.x0 - 1, box.y1 + 1, box.x1 + 1, box.y1 + 1, kFrame);
    canvas.Line(box.x0 - 1, box.y0 - 1, box.x0 - 1, box.y1 + 1, kFrame);
    canvas.Line(box.x1 + 1, box.y0 - 1, box.x1 + 1, box.y1 + 1, kFrame);
    if (lo < 0 && hi > 0) canvas.Line(box.x0, y_of(0), box.x1, y_of(0), kZeroColour);
    for (const PlotLine& line : panel.lines) {
      const size_t n = std::min(line.values.size(), plot.time_s.size());
      for (size_t i = 1; i < n; ++i) {
        canvas.Line(x_of(plot.time_s[i - 1]), y_of(line.values[i - 1]), x_of(plot.time_s[i]),
                    y_of(line.values[i]), line.colour);
      }
      if (n == 1) canvas.Set(x_of(plot.time_s[0]), y_of(line.values[0]), line.colour);
    }
    // the values at the panel's top and bottom edges, right-aligned against the frame
    const auto value_at = [&](double v, int y) {
      const std::string text = Number(v);
      canvas.Text(text, box.x0 - 4 - static_cast<int>(text.size()) * (kGlyphWidth_px + 1), y,
                  kText);
    };
    value_at(hi, box.y0);
    value_at(lo, box.y1 - kGlyphHeight_px + 1);
    canvas.Text(panel.label, box.x0 + 4, box.y0 + 4, kText);
  }
  // the time axis' ends under the last panel's frame
  if (panels > 0) {
    const PanelBox last = PlotPanelBox(panels - 1, panels);
    canvas.Text(Number(t0) + " s", last.x0, last.y1 + 3, kText);
    const std::string end = Number(t1) + " s";
    canvas.Text(end, last.x1 - static_cast<int>(end.size()) * (kGlyphWidth_px + 1), last.y1 + 3,
                kText);
  }
  return std::move(canvas.rgb());
}

std::vector<std::string> PlotStems(const std::vector<std::string>& log_files) {
  std::vector<std::string> stems;
  std::set<std::string> taken;
  for (const std::string& file : log_files) {
    const std::string stem = std::filesystem::path(file).stem().string();
    std::string unique = stem;
    for (int n = 2; taken.contains(unique); ++n) unique = stem + "-" + std::to_string(n);
    taken.insert(unique);
    stems.push_back(unique);
  }
  return stems;
}

void WritePlot(const std::string& path, const Plot& plot) {
  WritePng(path, kPlotWidth_px, kPlotHeight_px, RenderPlot(plot));
}

}  // namespace unimouse::fit
