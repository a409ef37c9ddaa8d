// SPDX-License-Identifier: GPL-3.0-or-later
// A flood-fill solver for the mms protocol, written as mms programs are: an API of small
// functions that print a command with std::endl and read the reply with std::getline. It maps
// the walls it sees, floods the distances to the centre over the walls known so far (unknown
// walls are taken as open), and steps to the nearest neighbour, straight on when that is one of
// them. It ends when it stands in the centre.
#include <deque>
#include <iostream>
#include <string>
#include <vector>

namespace api {

std::string Ask(const std::string& command) {
  std::cout << command << std::endl;
  std::string reply;
  std::getline(std::cin, reply);
  return reply;
}
int MazeWidth() { return std::stoi(Ask("mazeWidth")); }
int MazeHeight() { return std::stoi(Ask("mazeHeight")); }
bool WallFront() { return Ask("wallFront") == "true"; }
bool WallLeft() { return Ask("wallLeft") == "true"; }
bool WallRight() { return Ask("wallRight") == "true"; }
bool MoveForward() { return Ask("moveForward") == "ack"; }
void TurnLeft() { Ask("turnLeft"); }
void TurnRight() { Ask("turnRight"); }
void SetWall(int x, int y, char side) {
  std::cout << "setWall " << x << " " << y << " " << side << std::endl;
}
void SetColor(int x, int y, char color) {
  std::cout << "setColor " << x << " " << y << " " << color << std::endl;
}
void SetText(int x, int y, int value) {
  std::cout << "setText " << x << " " << y << " " << value << std::endl;
}

}  // namespace api

namespace {

// headings: 0 north, 1 east, 2 south, 3 west
const int kDx[4] = {0, 1, 0, -1};
const int kDy[4] = {1, 0, -1, 0};
const char kSide[4] = {'n', 'e', 's', 'w'};

struct Mouse {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> walls;  // bit h: a wall on side h, known
  std::vector<int> distance;
  int x = 0;
  int y = 0;
  int heading = 0;

  int Index(int cx, int cy) const { return cy * width + cx; }
  bool Inside(int cx, int cy) const { return cx >= 0 && cy >= 0 && cx < width && cy < height; }
  bool InCentre(int cx, int cy) const {
    const bool in_x = cx == (width - 1) / 2 || cx == width / 2;
    const bool in_y = cy == (height - 1) / 2 || cy == height / 2;
    return in_x && in_y;
  }

  void MarkWall(int h) {
    walls[Index(x, y)] |= 1 << h;
    const int nx = x + kDx[h];
    const int ny = y + kDy[h];
    if (Inside(nx, ny)) walls[Index(nx, ny)] |= 1 << ((h + 2) % 4);
    api::SetWall(x, y, kSide[h]);
  }

  void Sense() {
    if (api::WallFront()) MarkWall(heading);
    if (api::WallLeft()) MarkWall((heading + 3) % 4);
    if (api::WallRight()) MarkWall((heading + 1) % 4);
  }

  void Flood() {
    distance.assign(width * height, -1);
    std::deque<int> queue;
    for (int cy = 0; cy < height; ++cy) {
      for (int cx = 0; cx < width; ++cx) {
        if (InCentre(cx, cy)) {
          distance[Index(cx, cy)] = 0;
          queue.push_back(Index(cx, cy));
        }
      }
    }
    while (!queue.empty()) {
      const int cell = queue.front();
      queue.pop_front();
      const int cx = cell % width;
      const int cy = cell / width;
      for (int h = 0; h < 4; ++h) {
        const int nx = cx + kDx[h];
        const int ny = cy + kDy[h];
        if ((walls[cell] >> h & 1) || !Inside(nx, ny) || distance[Index(nx, ny)] >= 0) continue;
        distance[Index(nx, ny)] = distance[cell] + 1;
        queue.push_back(Index(nx, ny));
      }
    }
  }

  // the open neighbour nearest the centre, straight on first among equals
  int Choose() const {
    int best = -1;
    for (int turn : {0, 3, 1, 2}) {
      const int h = (heading + turn) % 4;
      const int nx = x + kDx[h];
      const int ny = y + kDy[h];
      if ((walls[Index(x, y)] >> h & 1) || !Inside(nx, ny)) continue;
      const int d = distance[Index(nx, ny)];
      if (d >= 0 && (best < 0 || d < distance[Index(x + kDx[best], y + kDy[best])])) best = h;
    }
    return best;
  }

  void Face(int h) {
    while (heading != h) {
      if ((heading + 3) % 4 == h) {
        api::TurnLeft();
        heading = h;
      } else {
        api::TurnRight();
        heading = (heading + 1) % 4;
      }
    }
  }
};

}  // namespace

int main() {
  std::cerr << "flood fill starting" << std::endl;
  Mouse mouse;
  mouse.width = api::MazeWidth();
  mouse.height = api::MazeHeight();
  mouse.walls.assign(mouse.width * mouse.height, 0);
  while (!mouse.InCentre(mouse.x, mouse.y)) {
    mouse.Sense();
    mouse.Flood();
    api::SetColor(mouse.x, mouse.y, 'c');
    api::SetText(mouse.x, mouse.y, mouse.distance[mouse.Index(mouse.x, mouse.y)]);
    const int h = mouse.Choose();
    if (h < 0) {
      std::cerr << "no way to the centre" << std::endl;
      return 1;
    }
    mouse.Face(h);
    if (!api::MoveForward()) {
      std::cerr << "crashed" << std::endl;
      return 1;
    }
    mouse.x += kDx[h];
    mouse.y += kDy[h];
  }
  std::cerr << "in the centre" << std::endl;
  return 0;
}
