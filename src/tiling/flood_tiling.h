// Discrete L-infinity Voronoi partition of the background triangles (paper, section 2.3):
// every tile grows from its generator triangle, one triangle at a time, in increasing
// order of d = max(|D.u|, |D.v|) / h(g), D = c(t) - c(g), (u, v) the cross frame at the
// generator's centroid. Dividing by the generator's size makes a tile's extent follow
// h (a multiplicatively weighted diagram): two generators split the segment between them
// in the ratio of their sizes. Tiles are connected by construction: a triangle joins a
// tile only from a neighbour already in it.
#pragma once

#include <cstdint>
#include <vector>

#include "fields/cross_field.h"
#include "mesh/background_mesh.h"
#include "tiling/tile_geometry.h"

namespace isoquad {

class LinfFlood {
 public:
  // Keeps references: mesh, geom and cross must outlive the object.
  LinfFlood(const BackgroundMesh& mesh, const TriangleGeometry& geom, const CrossField& cross);

  // Partitions the whole mesh. generator: #T distinct triangle ids. label: #F output.
  void flood(const std::vector<int>& generator, std::vector<int>& label);

  // The same partition, updated: `label` must be the result of the previous call (flood
  // or reflood) and `generator` have as many tiles. Only the tiles whose generator moved
  // and their neighbours are emptied and flooded again; the tiles around them may grow
  // into the emptied region. This is not exactly a full flood (a tile two rings away from
  // a moved generator keeps its triangles), but it touches a small fraction of the mesh
  // once the relaxation settles. changed: #T set to 1 for every tile that may have
  // gained or lost triangles. Falls back to a full flood when a generator lies outside
  // the emptied region.
  void reflood(const std::vector<int>& generator, std::vector<int>& label,
               std::vector<char>& changed);

  // Triangles assigned by the last call.
  std::size_t num_flooded() const { return num_flooded_; }

 private:
  void set_frame(int tile, int generator);
  float key(int tile, int f) const;
  void offer(int tile, int f);
  void run(std::vector<int>& label);

  const BackgroundMesh& mesh_;
  const TriangleGeometry& geom_;
  const CrossField& cross_;
  // Per tile: generator centroid, frame (u = (cu, su)), 1 / h at the generator.
  std::vector<double> gx_, gy_, cu_, su_, inv_h_;
  std::vector<int> generator_;      // of the last call
  std::vector<float> best_key_;     // #F smallest key offered so far
  std::vector<int> best_tile_;      // #F the tile that offered it
  std::vector<std::uint64_t> heap_;  // (key bits << 32) | triangle, a min-heap
  std::vector<int> stamp_;          // #F for the region searches of reflood
  int current_stamp_ = 0;
  std::vector<int> region_, stack_;
  std::size_t num_flooded_ = 0;
};

}  // namespace isoquad
