// SPDX-License-Identifier: GPL-3.0-or-later
// Top-down pictures of a maze, as figures 5.7-5.13 of the dissertation: visited cells shaded,
// known walls dark and walls not yet seen light, the open path orange and the closed path blue,
// the start and goal marked, and optionally a number in every cell. PNG and SVG.
#ifndef UNIMOUSE_MAZETOOLS_MAZE_PLOT_H_
#define UNIMOUSE_MAZETOOLS_MAZE_PLOT_H_

#include <cstdint>
#include <string>
#include <vector>

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

/// Returns RGB pixels, row by row from the top, Width x Height x 3 bytes.
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
