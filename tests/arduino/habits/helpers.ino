// A second tab: the IDE compiles it after the main one.
int twice(int x) { return 2 * x; }
