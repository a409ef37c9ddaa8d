// SPDX-License-Identifier: MIT
// A micromouse maze as the robot knows it (dissertation section 3.5.3): one byte per cell, the
// room fixed at compile time so that nothing is allocated: a Maze<W, H> holds any maze up to
// W x H cells, its size set at run time (resize), as the simulator tells it (maze info frame). The
// low nibble holds the walls and the high nibble which sides the robot has seen, with the
// UNIMOUSE_SIDE_* bits of the protocol, so that a cell goes to the simulator's debug channel as it
// is. (The dissertation's class ordered the wall bits up, right, left, down and left the high
// nibble unused.)
#ifndef UNIMOUSE_SIM_MAZE_H_
#define UNIMOUSE_SIM_MAZE_H_

#include <stdint.h>

#include "unimouse_protocol.h"

/// A compass direction in the maze: north is +y, east is +x. Turning right adds one.
enum class Direction : uint8_t { North = 0, East = 1, South = 2, West = 3 };

inline Direction turnRight(Direction d) {
  return static_cast<Direction>((static_cast<uint8_t>(d) + 1) & 3);
}
inline Direction turnLeft(Direction d) {
  return static_cast<Direction>((static_cast<uint8_t>(d) + 3) & 3);
}
inline Direction turnAround(Direction d) {
  return static_cast<Direction>((static_cast<uint8_t>(d) + 2) & 3);
}
/// The cell one step away in direction d (it may be outside the maze).
inline int8_t stepX(Direction d) {
  return d == Direction::East ? 1 : d == Direction::West ? -1 : 0;
}
inline int8_t stepY(Direction d) {
  return d == Direction::North ? 1 : d == Direction::South ? -1 : 0;
}
/// The protocol's side bit for a direction.
inline uint8_t sideBit(Direction d) { return static_cast<uint8_t>(1u << static_cast<uint8_t>(d)); }

template <uint8_t W, uint8_t H>
class Maze {
 public:
  static const uint8_t kWidth = W;
  static const uint8_t kHeight = H;

  /// A W x H maze with only its outer walls, which every contest maze has.
  Maze() { clear(); }

  /// Makes it a `width` x `height` maze (at most W x H) with only its outer walls; false, and
  /// unchanged, when it does not fit.
  bool resize(uint8_t width, uint8_t height) {
    if (width < 1 || height < 1 || width > W || height > H) return false;
    width_ = width;
    height_ = height;
    clear();
    return true;
  }
  uint8_t width() const { return width_; }
  uint8_t height() const { return height_; }

  /// Forgets every inner wall; the outer walls stay.
  void clear() {
    for (uint8_t x = 0; x < W; ++x) {
      for (uint8_t y = 0; y < H; ++y) {
        // an outer wall: there, and known; cells beyond the size are walled in on every side
        uint8_t walls = static_cast<uint8_t>(x < width_ && y < height_ ? 0 : 0x0F);
        if (y == height_ - 1) walls |= sideBit(Direction::North);
        if (x == width_ - 1) walls |= sideBit(Direction::East);
        if (y == 0) walls |= sideBit(Direction::South);
        if (x == 0) walls |= sideBit(Direction::West);
        cells_[x][y] = static_cast<uint8_t>(walls | walls << 4);
      }
    }
  }

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

  /// Puts a wall on side d of cell (x, y), and on the matching side of the neighbour.
  void placeWall(uint8_t x, uint8_t y, Direction d) { set(x, y, d, true); }
  /// Takes the wall away (it is then known to be open), on both cells that share it.
  void removeWall(uint8_t x, uint8_t y, Direction d) { set(x, y, d, false); }
  /// Forgets side d of cell (x, y), and the matching side of the neighbour: unseen again.
  void forget(uint8_t x, uint8_t y, Direction d) {
    const int nx = x + stepX(d), ny = y + stepY(d);
    if (!contains(nx, ny)) return;  // the outer walls stay
    cells_[x][y] &= static_cast<uint8_t>(~(sideBit(d) | sideBit(d) << 4));
    cells_[nx][ny] &= static_cast<uint8_t>(~(sideBit(turnAround(d)) | sideBit(turnAround(d)) << 4));
  }
  /// Whether side d of cell (x, y) has a wall; an unseen side has none until placed.
  bool hasWall(uint8_t x, uint8_t y, Direction d) const { return (cells_[x][y] & sideBit(d)) != 0; }
  /// Whether the wall on side d of (x, y) has been placed or removed, that is, seen.
  bool isKnown(uint8_t x, uint8_t y, Direction d) const {
    return (cells_[x][y] & (sideBit(d) << 4)) != 0;
  }
  /// The cell's byte: walls in the low nibble, known sides in the high one (UNIMOUSE_SIDE_*).
  uint8_t cell(uint8_t x, uint8_t y) const { return cells_[x][y]; }

 private:
  void set(uint8_t x, uint8_t y, Direction d, bool wall) {
    const int nx = x + stepX(d), ny = y + stepY(d);
    if (!contains(nx, ny)) return;  // the outer walls stay
    mark(x, y, d, wall);
    mark(static_cast<uint8_t>(nx), static_cast<uint8_t>(ny), turnAround(d), wall);
  }
  void mark(uint8_t x, uint8_t y, Direction d, bool wall) {
    uint8_t& c = cells_[x][y];
    c = static_cast<uint8_t>((c & ~sideBit(d)) | (wall ? sideBit(d) : 0) | sideBit(d) << 4);
  }

  uint8_t width_ = W;
  uint8_t height_ = H;
  uint8_t cells_[W][H];
};

#endif  // UNIMOUSE_SIM_MAZE_H_
