// SPDX-License-Identifier: GPL-3.0-or-later
// Top-down pictures of a maze, as figures 5.7-5.13 of the dissertation: visited cells shaded,
// known walls dark and walls not yet seen light, the open path orange and the closed path blue,
// the start and goal marked, and optionally a number in every cell. Over the true maze, what a
// firmware or an mms program reported (FirmwareBeliefs): the walls it believes in as blue strips
// along the wall, its cell colours filling the cells, its cell texts; and the mouse's cell
// framed. PNG and SVG.
#ifndef UNIMOUSE_MAZETOOLS_MAZE_PLOT_H_
#define UNIMOUSE_MAZETOOLS_MAZE_PLOT_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "firmware_beliefs.h"
#include "maze.h"
#include "maze_explorer.h"
#include "maze_solver.h"

namespace unimouse {

struct MazePicture {
  const Maze* maze = nullptr;                ///< the true maze
  const WallKnowledge* knowledge = nullptr;  ///< what a mouse knows and where it has been
  std::vector<uint8_t> visited;              ///< without knowledge: per cell, from the south-west
  MazePath open_path;                        ///< drawn orange
  MazePath closed_path;                      ///< drawn blue
  std::vector<int> numbers;                  ///< per cell, -1 for none
  const FirmwareBeliefs* beliefs = nullptr;  ///< believed walls, cell colours and texts
  std::optional<Cell> mouse;                 ///< framed in magenta
};

/// Pixel geometry of the PNG: where a cell's centre lands.
struct PlotGeometry {
  int cell_px = 32;
  int margin_px = 16;
  int Width(const Maze& m) const { return 2 * margin_px + cell_px * m.width(); }
  int Height(const Maze& m) const { return 2 * margin_px + cell_px * m.height(); }
  int CentreX(const Maze&, int x) const { return margin_px + cell_px * x + cell_px / 2; }
  int CentreY(const Maze& m, int y) const {
    return margin_px + cell_px * (m.height() - 1 - y) + cell_px / 2;
  }
};

/// Returns RGB pixels, row by row from the top, Width x Height x 3 bytes. A cell's text (or
/// number) is drawn in the 5 x 7 bitmap font, glyphs 6 font pixels apart: one row of up to five
/// characters, or the first five over the rest; a font pixel is s x s pixels, s the largest whole
/// number >= 1 with 6 s x columns <= cell - 4 and 8 s x rows <= cell - 4 (columns: the longest
/// row's characters); a row of n characters starts (6 n - 1) s / 2 left of the cell centre, the
/// first row (8 rows - 1) s / 2 above it (rounded towards zero), the second 8 s below the first.
std::vector<uint8_t> RenderMazePixels(const MazePicture& picture, const PlotGeometry& g = {});

/// Writes a PNG; throws InputError if the file cannot be written.
void WriteMazePng(const MazePicture& picture, const std::string& path);

/// Returns an SVG document.
std::string RenderMazeSvg(const MazePicture& picture);

/// Writes a PNG or an SVG, by the file's extension.
void WriteMazePicture(const MazePicture& picture, const std::string& path);

/// Writes an RGB image as a PNG.
void WritePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace unimouse

#endif  // UNIMOUSE_MAZETOOLS_MAZE_PLOT_H_
