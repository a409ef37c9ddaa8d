// SPDX-License-Identifier: GPL-3.0-or-later
// The picture of an mms run: the true maze, and over it what the program displayed (the walls it
// set, its cell colours and texts) and the mouse's last cell, drawn as a firmware's beliefs are.
#ifndef UNIMOUSE_MMS_MMS_PICTURE_H_
#define UNIMOUSE_MMS_MMS_PICTURE_H_

#include <string>

#include "mms_protocol.h"

namespace unimouse {

/// Writes out_dir/maze.png and out_dir/maze.svg. Throws InputError when they cannot be written.
void WriteMmsPictures(const Maze& maze, const MmsWorld& world, const std::string& out_dir);

}  // namespace unimouse

#endif  // UNIMOUSE_MMS_MMS_PICTURE_H_
