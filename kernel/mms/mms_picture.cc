// SPDX-License-Identifier: GPL-3.0-or-later
#include "mms_picture.h"

#include <filesystem>

#include "maze_plot.h"

namespace unimouse {

void WriteMmsPictures(const Maze& maze, const MmsWorld& world, const std::string& out_dir) {
  const FirmwareBeliefs beliefs = world.Beliefs();
  MazePicture picture;
  picture.maze = &maze;
  picture.beliefs = &beliefs;
  // between two cells (a half-step) the mouse has no cell to frame
  if (maze.Contains(world.cell())) picture.mouse = world.cell();
  const std::filesystem::path base = std::filesystem::path(out_dir) / "maze";
  WriteMazePicture(picture, base.string() + ".png");
  WriteMazePicture(picture, base.string() + ".svg");
}

}  // namespace unimouse
