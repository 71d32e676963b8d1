// Point location in the background mesh: which triangle contains a point, with its
// barycentric coordinates. A uniform grid of triangle bounding boxes; used to evaluate
// the fields at arbitrary points (quad centroids, quad vertices).
#pragma once

#include <array>
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

 private:
  const BackgroundMesh* mesh_;
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_, items_;  // CSR: triangles overlapping each cell
};

// Barycentric coordinates of p in triangle (a, b, c).
std::array<double, 3> barycentric(const Point2& a, const Point2& b, const Point2& c, const Point2& p);

}  // namespace isoquad
