// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze_plot.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "bitmap_font.h"
#include "png_file.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using Rgb = Rgb8;

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
constexpr Rgb kBelievedWall{51, 140, 255};  // the 3D pictures' believed walls
constexpr Rgb kMouse{220, 0, 140};
constexpr Rgb kTextOnDark{255, 255, 255};
constexpr int kRowChars = 5;  // mms's cell text: two rows of five

// light text on a dark fill, dark text on a light one
Rgb TextColourOn(Rgb fill) {
  return 299 * fill.r + 587 * fill.g + 114 * fill.b < 128 * 1000 ? kTextOnDark : kKnownWall;
}

std::string Hex(Rgb c) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

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

  // a cell's text in the bitmap font, laid out as maze_plot.h says
  void Text(const std::string& text, int cx, int cy, int cell_px, Rgb c) {
    const int rows = text.size() > kRowChars ? 2 : 1;
    const int columns = std::min(static_cast<int>(text.size()), kRowChars);
    if (columns == 0) return;
    const int scale =
        std::max(1, std::min((cell_px - 4) / (6 * columns), (cell_px - 4) / (8 * rows)));
    for (int row = 0; row < rows; ++row) {
      const std::string line = text.substr(static_cast<size_t>(row * kRowChars), kRowChars);
      int x = cx - (6 * static_cast<int>(line.size()) - 1) * scale / 2;
      const int y = cy - (8 * rows - 1) * scale / 2 + 8 * scale * row;
      for (char ch : line) {
        const Glyph& glyph = GlyphOf(ch);
        for (int gy = 0; gy < kGlyphHeight_px; ++gy) {
          for (int gx = 0; gx < kGlyphWidth_px; ++gx) {
            if (glyph[static_cast<size_t>(gy)] >> (kGlyphWidth_px - 1 - gx) & 1) {
              Fill(x + gx * scale, y + gy * scale, x + (gx + 1) * scale, y + (gy + 1) * scale, c);
            }
          }
        }
        x += 6 * scale;
      }
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

// the side's bit in FirmwareBeliefs: north 1, east 2, south 4, west 8
uint8_t SideBit(Heading h) {
  switch (h) {
    case Heading::kNorth:
      return 1;
    case Heading::kEast:
      return 2;
    case Heading::kSouth:
      return 4;
    case Heading::kWest:
      return 8;
  }
  return 0;
}

// every wall the report says is there, on the cell side it was reported for
template <class F>
void ForEachBelievedWall(const MazePicture& p, F draw) {
  if (p.beliefs == nullptr) return;
  for (const auto& [at, w] : p.beliefs->walls) {
    const Cell c{at.first, at.second};
    if (!p.maze->Contains(c)) continue;
    for (Heading h : {Heading::kNorth, Heading::kEast, Heading::kSouth, Heading::kWest}) {
      if (w.known & w.walls & SideBit(h)) draw(c, h);
    }
  }
}

// how a cell looks: visited, goal or start, the colour the report gave it over those; the
// reported text, else its number
struct CellLook {
  Rgb fill = kBackground;
  std::string text;
  Rgb text_colour = kNumber;
};
CellLook LookOf(const MazePicture& p, Cell c) {
  CellLook look;
  if (Visited(p, c)) look.fill = kVisited;
  if (p.maze->IsGoal(c)) look.fill = kGoal;
  if (c == p.maze->start()) look.fill = kStart;
  const size_t i = static_cast<size_t>(c.y * p.maze->width() + c.x);
  if (!p.numbers.empty() && p.numbers[i] >= 0) look.text = std::to_string(p.numbers[i]);
  if (p.beliefs == nullptr) return look;
  const auto colour = p.beliefs->colours.find({c.x, c.y});
  if (colour != p.beliefs->colours.end()) {
    look.fill = CellColourOf(colour->second).value_or(look.fill);
  }
  const auto text = p.beliefs->texts.find({c.x, c.y});
  if (text != p.beliefs->texts.end()) {
    look.text = text->second.substr(0, kMaxCellText);
    look.text_colour = TextColourOn(look.fill);
  }
  return look;
}

// the rectangle of a wall `width` pixels thick, `inset` short of each post
struct Rect {
  int x0, y0, x1, y1;
};
Rect WallRect(const PlotGeometry& g, const Maze& m, Cell c, Heading h, int width, int inset) {
  const int cx = g.CentreX(m, c.x), cy = g.CentreY(m, c.y), half = g.cell_px / 2;
  const int lo = -width / 2, hi = width - width / 2;
  switch (h) {
    case Heading::kSouth:
      return {cx - half + inset, cy + half + lo, cx + half - inset, cy + half + hi};
    case Heading::kNorth:
      return {cx - half + inset, cy - half + lo, cx + half - inset, cy - half + hi};
    case Heading::kWest:
      return {cx - half + lo, cy - half + inset, cx - half + hi, cy + half - inset};
    case Heading::kEast:
      return {cx + half + lo, cy - half + inset, cx + half + hi, cy + half - inset};
  }
  return {};
}

}  // namespace

std::vector<uint8_t> RenderMazePixels(const MazePicture& p, const PlotGeometry& g) {
  const Maze& m = *p.maze;
  Canvas canvas(g.Width(m), g.Height(m));
  const int cell = g.cell_px, half = cell / 2;

  // cells: visited, start, goals, colours, and their texts or numbers
  for (int y = 0; y < m.height(); ++y) {
    for (int x = 0; x < m.width(); ++x) {
      const Cell c{x, y};
      const CellLook look = LookOf(p, c);
      const int cx = g.CentreX(m, x), cy = g.CentreY(m, y);
      canvas.Fill(cx - half, cy - half, cx + half, cy + half, look.fill);
      canvas.Text(look.text, cx, cy, cell, look.text_colour);
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

  // walls, believed walls as a strip along their middle, posts on top
  auto fill = [&](Rect r, Rgb colour) { canvas.Fill(r.x0, r.y0, r.x1, r.y1, colour); };
  ForEachWall(m, [&](Cell c, Heading h) {
    fill(WallRect(g, m, c, h, 4, 0), Known(p, c, h) ? kKnownWall : kUnknownWall);
  });
  ForEachBelievedWall(p,
                      [&](Cell c, Heading h) { fill(WallRect(g, m, c, h, 2, 2), kBelievedWall); });
  for (int y = 0; y <= m.height(); ++y) {
    for (int x = 0; x <= m.width(); ++x) {
      const int px = g.margin_px + cell * x, py = g.margin_px + cell * (m.height() - y);
      canvas.Fill(px - 2, py - 2, px + 2, py + 2, kPost);
    }
  }
  if (p.mouse && m.Contains(*p.mouse)) {
    // a frame 2 pixels wide, 5 inside the cell's edges
    const int cx = g.CentreX(m, p.mouse->x), cy = g.CentreY(m, p.mouse->y), r = half - 5;
    canvas.Fill(cx - r, cy - r, cx + r, cy - r + 2, kMouse);
    canvas.Fill(cx - r, cy + r - 2, cx + r, cy + r, kMouse);
    canvas.Fill(cx - r, cy - r, cx - r + 2, cy + r, kMouse);
    canvas.Fill(cx + r - 2, cy - r, cx + r, cy + r, kMouse);
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
      const CellLook look = LookOf(p, {x, y});
      if (look.fill != kBackground) {
        out << "<rect class='cell' x='" << g.CentreX(m, x) - half << "' y='"
            << g.CentreY(m, y) - half << "' width='" << cell << "' height='" << cell << "' fill='"
            << Hex(look.fill) << "'/>\n";
      }
      // one line of up to five characters, or two, as in the PNG
      const int rows = look.text.empty() ? 0 : look.text.size() > kRowChars ? 2 : 1;
      for (int row = 0; row < rows; ++row) {
        out << "<text x='" << g.CentreX(m, x) << "' y='"
            << g.CentreY(m, y) + 4 + 12 * row - 6 * (rows - 1)
            << "' font-family='monospace' font-size='11' text-anchor='middle' fill='"
            << Hex(look.text_colour) << "'>"
            << XmlEscaped(look.text.substr(static_cast<size_t>(row * kRowChars), kRowChars))
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
  auto line = [&](Rect r, const char* name, int width, Rgb colour) {
    out << "<line class='" << name << "' x1='" << r.x0 << "' y1='" << r.y0 << "' x2='" << r.x1
        << "' y2='" << r.y1 << "' stroke-width='" << width << "' stroke='" << Hex(colour)
        << "'/>\n";
  };
  ForEachWall(m, [&](Cell c, Heading h) {
    const bool known = Known(p, c, h);
    line(WallRect(g, m, c, h, 0, 0), known ? "wall" : "unknown-wall", 4,
         known ? kKnownWall : kUnknownWall);
  });
  ForEachBelievedWall(p, [&](Cell c, Heading h) {
    line(WallRect(g, m, c, h, 0, 2), "believed-wall", 2, kBelievedWall);
  });
  if (p.mouse && m.Contains(*p.mouse)) {
    out << "<rect class='mouse' x='" << g.CentreX(m, p.mouse->x) - half + 6 << "' y='"
        << g.CentreY(m, p.mouse->y) - half + 6 << "' width='" << cell - 12 << "' height='"
        << cell - 12 << "' fill='none' stroke-width='2' stroke='" << Hex(kMouse) << "'/>\n";
  }
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
