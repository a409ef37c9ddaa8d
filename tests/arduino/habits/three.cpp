// A .cpp file beside the sketch: compiled on its own, with Arduino.h included as on a board.
#include <Arduino.h>

#include "three.h"

int addThree(int x) { return x + 3; }
