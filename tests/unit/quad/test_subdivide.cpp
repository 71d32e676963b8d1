// Barycentric subdivision of tiles (paper, 2.6): where the tile centre goes.
#include "quad/subdivide_tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/fields_job.h"
#include "mesh/boundary_corners.h"
#include "tiling/meta_graph.h"
#include "unit/mesh/test_domains.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

double flattest_quad(const QuadMesh& m) {
  double worst = 1.0;
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q) worst = std::min(worst, quad_convexity(m, q));
  return worst;
}

}  // namespace

TEST(SubdivideTiles, BentTileGetsACentreInsideIt) {
  // A C-shaped domain (three quarters of an annulus, radii 800 and 1000 m) as one tile
  // with its 4 corners at the ends: its centroid lies at a radius of about 270 m, in the
  // hole, and the quads around it fold. The centre moves to a triangle of the tile and
  // the flattest quad gets better.
  Ring ring;
  const int n = 48;
  for (int i = 0; i <= n; ++i) {
    const double a = 1.5 * kPi * i / n;
    ring.push_back({1000.0 * std::cos(a), 1000.0 * std::sin(a)});
  }
  for (int i = n; i >= 0; --i) {
    const double a = 1.5 * kPi * i / n;
    ring.push_back({800.0 * std::cos(a), 800.0 * std::sin(a)});
  }
  Domain d;
  d.polygons.push_back({ring, {}});
  FieldsOptions o;
  o.sizing.automatic = false;
  o.sizing.constant_m = 100.0;
  o.cross.source = CrossSource::constant;
  FieldsResult f;
  build_fields_on_domain(d, o, f);
  // Corners only where the ring turns by 90 degrees: the four ends of the C.
  for (BoundaryChain& chain : f.mesh.chains)
    for (std::size_t k = 0; k < chain.vertices.size(); ++k)
      chain.is_corner[k] = std::abs(chain.turning_angle_deg[k]) > 60.0 ? 1 : 0;
  Tiling tiling;
  tiling.label.assign(f.mesh.triangles.size(), 0);
  tiling.generator = {0};
  const MetaGraph graph = build_meta_graph(f.mesh, tiling);
  ASSERT_EQ(graph.tiles[0].edges.size(), 4u);

  SubdivideParams centroid_only;
  centroid_only.centre_min_convexity = -2.0;  // never replaced
  const QuadMesh at_centroid = subdivide_tiles(f.mesh, tiling, graph, centroid_only);
  const QuadMesh moved = subdivide_tiles(f.mesh, tiling, graph);
  ASSERT_EQ(moved.quads.size(), 4u);
  const Point2 c0 = at_centroid.points[at_centroid.quads[0][0]];
  EXPECT_LT(std::hypot(c0.x, c0.y), 400.0);
  const Point2 c = moved.points[moved.quads[0][0]];
  const double r = std::hypot(c.x, c.y);
  EXPECT_GT(r, 800.0);
  EXPECT_LT(r, 1000.0);
  EXPECT_LT(flattest_quad(at_centroid), 0.0);
  EXPECT_GT(flattest_quad(moved), flattest_quad(at_centroid));
}
