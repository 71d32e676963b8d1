// Point location in the background mesh: which triangle contains a point, with its
// barycentric coordinates. A uniform grid of triangle bounding boxes; used to evaluate
// the fields at arbitrary points (quad centroids, quad vertices).
#pragma once

#include <array>
#include <mutex>
#include <vector>

#include "core/geometry.h"
#include "mesh/background_mesh.h"

namespace isoquad {

struct Location {
  int triangle = -1;                 // -1 when the point is outside the mesh
  std::array<double, 3> bary{0, 0, 0};  // weights of triangles[triangle][0..2]
  bool inside = false;               // the point is in the triangle (not clamped)
};

class TriangleLocator {
 public:
  explicit TriangleLocator(const BackgroundMesh& mesh);
  // The containing triangle; a point outside the mesh (e.g. on a chord of a curved
  // boundary) gets the nearest triangle, with its barycentric coordinates clamped.
  Location locate(const Point2& p) const;
  // The same, first trying triangle `hint` (e.g. where a moving point was last): a point
  // well inside it (every barycentric coordinate over 1e-9) is in no other triangle, so
  // the answer is the one locate(p) gives, without the search.
  Location locate(const Point2& p, int hint) const;
  // locate(p) visiting every ring of cells, the empty ones too (for tests: the same
  // answer, slower by the empty rings).
  Location locate_visiting_every_ring(const Point2& p) const { return search(p, false); }

 private:
  Location search(const Point2& p, bool skip_empty_rings) const;
  void find_empty_rings() const;
  const BackgroundMesh* mesh_;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_, items_;  // CSR: triangles overlapping each cell
  // Per cell, the rings round it that hold no triangle (its chessboard distance to the
  // nearest cell that holds one), found at the first point located two rings or more
  // from any triangle: the search starts past them. An int a cell, as start_ holds;
  // never made when every point located lies within a ring of the mesh.
  mutable std::once_flag empty_rings_once_;
  mutable std::vector<int> empty_rings_;
};

// Barycentric coordinates of p in triangle (a, b, c).
std::array<double, 3> barycentric(const Point2& a, const Point2& b, const Point2& c, const Point2& p);

}  // namespace isoquad
