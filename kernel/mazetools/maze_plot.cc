// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze_plot.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "png_file.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Rgb {
  uint8_t r, g, b;
};

constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kVisited{204, 230, 255};
constexpr Rgb kStart{170, 225, 170};
constexpr Rgb kGoal{255, 215, 160};
constexpr Rgb kKnownWall{30, 30, 30};
constexpr Rgb kUnknownWall{200, 200, 200};
constexpr Rgb kPost{30, 30, 30};
constexpr Rgb kOpenPath{255, 140, 0};
constexpr Rgb kClosedPath{31, 95, 214};
constexpr Rgb kNumber{90, 90, 90};

std::string Hex(Rgb c) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

// 3 x 5 digits, one row of three bits per entry, top row first
constexpr uint8_t kDigits[10][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};

class Canvas {
 public:
  Canvas(int w, int h)
      : w_(w), h_(h), rgb_(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 255) {}

  void Fill(int x0, int y0, int x1, int y1, Rgb c) {
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, w_), y1 = std::min(y1, h_);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        uint8_t* p =
            &rgb_[(static_cast<size_t>(y) * static_cast<size_t>(w_) + static_cast<size_t>(x)) * 3];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
    }
  }

  // a number centred on (cx, cy), each font pixel `scale` pixels wide
  void Number(int value, int cx, int cy, int scale, Rgb c) {
    const std::string text = std::to_string(value);
    const int width = static_cast<int>(text.size()) * 4 * scale - scale;
    int x = cx - width / 2;
    const int y = cy - 5 * scale / 2;
    for (char ch : text) {
      if (ch >= '0' && ch <= '9') {
        for (int row = 0; row < 5; ++row) {
          for (int col = 0; col < 3; ++col) {
            if (kDigits[ch - '0'][row] >> (2 - col) & 1) {
              Fill(x + col * scale, y + row * scale, x + (col + 1) * scale, y + (row + 1) * scale,
                   c);
            }
          }
        }
      }
      x += 4 * scale;
    }
  }

  std::vector<uint8_t>& rgb() { return rgb_; }

 private:
  int w_, h_;
  std::vector<uint8_t> rgb_;
};

bool Known(const MazePicture& p, Cell c, Heading h) {
  return p.knowledge == nullptr || p.knowledge->Known(c, h);
}

bool Visited(const MazePicture& p, Cell c) {
  if (p.knowledge != nullptr) return p.knowledge->Visited(c);
  return !p.visited.empty() && p.visited[static_cast<size_t>(c.y * p.maze->width() + c.x)];
}

// every wall once: cells' south and west sides, plus the north and east edges
template <class F>
void ForEachWall(const Maze& m, F draw) {
  for (int y = 0; y < m.height(); ++y) {
    for (int x = 0; x < m.width(); ++x) {
      for (Heading h : {Heading::kSouth, Heading::kWest}) {
        if (m.HasWall({x, y}, h)) draw(Cell{x, y}, h);
      }
      if (y == m.height() - 1 && m.HasWall({x, y}, Heading::kNorth))
        draw(Cell{x, y}, Heading::kNorth);
      if (x == m.width() - 1 && m.HasWall({x, y}, Heading::kEast)) draw(Cell{x, y}, Heading::kEast);
    }
  }
}

}  // namespace

std::vector<uint8_t> RenderMazePixels(const MazePicture& p, const PlotGeometry& g) {
  const Maze& m = *p.maze;
  Canvas canvas(g.Width(m), g.Height(m));
  const int cell = g.cell_px, half = cell / 2;

  // cells: visited, start, goals
  for (int y = 0; y < m.height(); ++y) {
    for (int x = 0; x < m.width(); ++x) {
      const Cell c{x, y};
      Rgb fill = kBackground;
      if (Visited(p, c)) fill = kVisited;
      if (m.IsGoal(c)) fill = kGoal;
      if (c == m.start()) fill = kStart;
      const int cx = g.CentreX(m, x), cy = g.CentreY(m, y);
      canvas.Fill(cx - half, cy - half, cx + half, cy + half, fill);
      if (!p.numbers.empty() && p.numbers[static_cast<size_t>(y * m.width() + x)] >= 0) {
        canvas.Number(p.numbers[static_cast<size_t>(y * m.width() + x)], cx, cy, 2, kNumber);
      }
    }
  }

  // paths through cell centres; the open one a little up-left, the closed one down-right, so
  // that both show where they share cells
  auto draw_path = [&](const MazePath& path, int offset, Rgb colour) {
    for (size_t i = 1; i < path.cells.size(); ++i) {
      const int x0 = g.CentreX(m, path.cells[i - 1].x) + offset;
      const int y0 = g.CentreY(m, path.cells[i - 1].y) + offset;
      const int x1 = g.CentreX(m, path.cells[i].x) + offset;
      const int y1 = g.CentreY(m, path.cells[i].y) + offset;
      canvas.Fill(std::min(x0, x1) - 1, std::min(y0, y1) - 1, std::max(x0, x1) + 2,
                  std::max(y0, y1) + 2, colour);
    }
  };
  draw_path(p.open_path, -3, kOpenPath);
  draw_path(p.closed_path, 3, kClosedPath);

  // walls and posts on top
  ForEachWall(m, [&](Cell c, Heading h) {
    const int cx = g.CentreX(m, c.x), cy = g.CentreY(m, c.y);
    const Rgb colour = Known(p, c, h) ? kKnownWall : kUnknownWall;
    switch (h) {
      case Heading::kSouth:
        canvas.Fill(cx - half, cy + half - 2, cx + half, cy + half + 2, colour);
        break;
      case Heading::kNorth:
        canvas.Fill(cx - half, cy - half - 2, cx + half, cy - half + 2, colour);
        break;
      case Heading::kWest:
        canvas.Fill(cx - half - 2, cy - half, cx - half + 2, cy + half, colour);
        break;
      case Heading::kEast:
        canvas.Fill(cx + half - 2, cy - half, cx + half + 2, cy + half, colour);
        break;
    }
  });
  for (int y = 0; y <= m.height(); ++y) {
    for (int x = 0; x <= m.width(); ++x) {
      const int px = g.margin_px + cell * x, py = g.margin_px + cell * (m.height() - y);
      canvas.Fill(px - 2, py - 2, px + 2, py + 2, kPost);
    }
  }
  return std::move(canvas.rgb());
}

void WriteMazePng(const MazePicture& picture, const std::string& path) {
  const PlotGeometry g;
  WritePng(path, g.Width(*picture.maze), g.Height(*picture.maze), RenderMazePixels(picture, g));
}

std::string RenderMazeSvg(const MazePicture& p) {
  const Maze& m = *p.maze;
  const PlotGeometry g;
  const int cell = g.cell_px, half = cell / 2;
  std::ostringstream out;
  out << "<svg xmlns='http://www.w3.org/2000/svg' width='" << g.Width(m) << "' height='"
      << g.Height(m) << "' viewBox='0 0 " << g.Width(m) << ' ' << g.Height(m) << "'>\n"
      << "<rect width='100%' height='100%' fill='" << Hex(kBackground) << "'/>\n";
  for (int y = 0; y < m.height(); ++y) {
    for (int x = 0; x < m.width(); ++x) {
      const Cell c{x, y};
      std::string fill;
      if (Visited(p, c)) fill = Hex(kVisited);
      if (m.IsGoal(c)) fill = Hex(kGoal);
      if (c == m.start()) fill = Hex(kStart);
      if (!fill.empty()) {
        out << "<rect class='cell' x='" << g.CentreX(m, x) - half << "' y='"
            << g.CentreY(m, y) - half << "' width='" << cell << "' height='" << cell << "' fill='"
            << fill << "'/>\n";
      }
      if (!p.numbers.empty() && p.numbers[static_cast<size_t>(y * m.width() + x)] >= 0) {
        out << "<text x='" << g.CentreX(m, x) << "' y='" << g.CentreY(m, y) + 4
            << "' font-family='sans-serif' font-size='11' text-anchor='middle' fill='"
            << Hex(kNumber) << "'>" << p.numbers[static_cast<size_t>(y * m.width() + x)]
            << "</text>\n";
      }
    }
  }
  auto draw_path = [&](const MazePath& path, int offset, Rgb colour, const char* name) {
    if (path.cells.size() < 2) return;
    out << "<polyline class='" << name << "' fill='none' stroke-width='3' stroke='" << Hex(colour)
        << "' points='";
    for (Cell c : path.cells) {
      out << g.CentreX(m, c.x) + offset << ',' << g.CentreY(m, c.y) + offset << ' ';
    }
    out << "'/>\n";
  };
  draw_path(p.open_path, -3, kOpenPath, "open-path");
  draw_path(p.closed_path, 3, kClosedPath, "closed-path");
  ForEachWall(m, [&](Cell c, Heading h) {
    const int cx = g.CentreX(m, c.x), cy = g.CentreY(m, c.y);
    int x0 = cx - half, y0 = cy - half, x1 = cx + half, y1 = cy + half;
    if (h == Heading::kSouth) y0 = y1;
    if (h == Heading::kNorth) y1 = y0;
    if (h == Heading::kWest) x1 = x0;
    if (h == Heading::kEast) x0 = x1;
    out << "<line class='" << (Known(p, c, h) ? "wall" : "unknown-wall") << "' x1='" << x0
        << "' y1='" << y0 << "' x2='" << x1 << "' y2='" << y1 << "' stroke-width='4' stroke='"
        << Hex(Known(p, c, h) ? kKnownWall : kUnknownWall) << "'/>\n";
  });
  out << "</svg>\n";
  return out.str();
}

void WriteMazePicture(const MazePicture& picture, const std::string& path) {
  if (path.size() > 4 && path.substr(path.size() - 4) == ".svg") {
    WriteTextFile(path, RenderMazeSvg(picture));
  } else if (path.size() > 4 && path.substr(path.size() - 4) == ".png") {
    WriteMazePng(picture, path);
  } else {
    throw InputError(path + ": a picture's name ends in .png or .svg");
  }
}

}  // namespace unimouse
