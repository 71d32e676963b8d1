// Tiles: unions of background triangles (paper, section 2.1), as one label per triangle.
// Every tiling step (2.2 to 2.5) reads and writes this struct.
#pragma once

#include <vector>

namespace isoquad {

struct Tiling {
  std::vector<int> label;      // #F tile id of each background triangle, in [0, #T)
  std::vector<int> generator;  // #T generator triangle of each tile (relaxation), -1 if none
  int num_tiles() const { return static_cast<int>(generator.size()); }
};

}  // namespace isoquad
