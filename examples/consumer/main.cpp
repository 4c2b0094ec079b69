// The consuming project's "game": it only says where its baked lighting is. A real one would open it
// with walkrad's runtime (runtime/include/walkrad/runtime/player.h).
#include <cstdio>

int main() {
  std::printf("level lighting: %s\n", LEVEL_BAKE);
  return 0;
}
