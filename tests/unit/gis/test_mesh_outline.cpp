// mesh_outline on small grids: holes, holes and parts touching at a node, clockwise
// files, triangles beside quadrangles, and the meshes whose boundary is not loops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "gis/mesh_outline.h"

using namespace isoquad;

namespace {

// An n x n grid of unit quads (node (i, j) is j * (n + 1) + i), counter-clockwise,
// without the cells in `removed` ({i, j} of the cell's lower left node).
struct Grid {
  std::vector<Point2> points;
  std::vector<std::array<int, 4>> quads;
};

Grid grid(int n, const std::vector<std::array<int, 2>>& removed = {}) {
  Grid g;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) g.points.push_back({double(i), double(j)});
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      if (std::find(removed.begin(), removed.end(), std::array<int, 2>{i, j}) == removed.end())
        g.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return g;
}

double loop_area(const Grid& g, const std::vector<int>& loop) {
  Ring ring;
  for (int v : loop) ring.push_back(g.points[v]);
  return signed_area(ring);
}

std::vector<std::vector<int>> outline(const Grid& g,
                                      const std::vector<std::array<int, 3>>& triangles = {}) {
  return mesh_outline(g.points, g.quads, triangles, "grid.gr3");
}

std::string outline_error(const Grid& g, const std::vector<std::array<int, 3>>& triangles = {}) {
  try {
    outline(g, triangles);
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input);
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MeshOutline, OuterLoopAndAHole) {
  const Grid g = grid(3, {{1, 1}});
  const auto loops = outline(g);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0].size(), 12u);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[0]), 9.0);
  EXPECT_EQ(loops[0].front(), 0);  // traced from the smallest node
  EXPECT_EQ(loops[1].size(), 4u);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[1]), -1.0);
}

// Each loop simple; their areas (signed: holes negative).
std::vector<double> simple_loop_areas(const Grid& g) {
  std::vector<double> areas;
  for (const auto& loop : outline(g)) {
    std::vector<int> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end())
        << "a loop passes a node twice";
    areas.push_back(loop_area(g, loop));
  }
  return areas;
}

TEST(MeshOutline, LoopsTouchingAtANodeStaySimple) {
  // The cell (0, 0) joined to the rest at the node (1, 1) alone.
  EXPECT_EQ(simple_loop_areas(grid(3, {{1, 0}, {0, 1}})), (std::vector<double>{1.0, 6.0}));
  // A hole touching a notch of the outer boundary at the node (1, 1).
  EXPECT_EQ(simple_loop_areas(grid(3, {{0, 0}, {1, 1}})), (std::vector<double>{8.0, -1.0}));
}

TEST(MeshOutline, TwoHolesMeetingAtANode) {
  const Grid g = grid(4, {{1, 1}, {2, 2}});
  const auto loops = outline(g);
  ASSERT_EQ(loops.size(), 3u);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[0]), 16.0);
  EXPECT_EQ(loops[1].size(), 4u);
  EXPECT_EQ(loops[2].size(), 4u);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[1]), -1.0);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[2]), -1.0);
}

TEST(MeshOutline, ClockwiseElementsGiveTheSameLoops) {
  Grid g = grid(3, {{1, 1}});
  const auto counter_clockwise = outline(g);
  for (auto& q : g.quads) std::reverse(q.begin(), q.end());
  EXPECT_EQ(outline(g), counter_clockwise);
}

TEST(MeshOutline, TrianglesBesideQuadrangles) {
  Grid g = grid(2);
  // The cell (1, 1) (nodes 4, 5, 8, 7) as two triangles.
  g.quads.pop_back();
  const auto loops = outline(g, {{4, 5, 8}, {4, 8, 7}});
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 8u);
  EXPECT_DOUBLE_EQ(loop_area(g, loops[0]), 4.0);
}

TEST(MeshOutline, ErrorsNameTheFileAndTheNodes) {
  EXPECT_NE(outline_error(Grid{}).find("'grid.gr3' has no elements"), std::string::npos);
  // The edge 1-4 (nodes 2 and 5 in the file) a side of three elements.
  Grid g = grid(2);
  g.quads.push_back({1, 4, 5, 2});
  EXPECT_NE(outline_error(g).find("nodes 2 and 5 is a side of three or more"), std::string::npos)
      << outline_error(g);
  // The second cell clockwise: the boundary stops at node 1 (2 in the file).
  g = grid(2);
  g.quads.resize(2);
  std::reverse(g.quads[1].begin(), g.quads[1].end());
  EXPECT_NE(outline_error(g).find("does not close at node 2"), std::string::npos)
      << outline_error(g);
}

namespace {

// A ring of quads round the globe in longitudes, from `south` to `north` degrees of
// latitude, `n` quads each `360 / n` wide from `west`, longitudes as a file writes them
// in [lo, lo + 360): the last quad (or one in the middle) crosses the cut.
ReadMesh globe_band(int n, double south, double north, double west, double lo) {
  ReadMesh m;
  m.crs = "EPSG:4326";
  auto lon = [&](int i) {
    double x = west + 360.0 * i / n;
    while (x >= lo + 360.0) x -= 360.0;
    while (x < lo) x += 360.0;
    return x;
  };
  for (int i = 0; i < n; ++i)
    m.points.push_back({lon(i), south}), m.points.push_back({lon(i), north});
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * ((i + 1) % n);
    m.quads.push_back({a, b, b + 1, a + 1});
  }
  return m;
}

// Rings after the first are holes.
double polygon_area(const SourcePolygon& p) {
  double a = 0;
  for (const Ring& r : p.rings) a += signed_area(r);
  return a;
}

}  // namespace

TEST(MeshOutline, AGridRoundTheGlobeIsAnAnnulusRoundAPole) {
  // Between 20 S and 40 N, in [0, 360): no cut in longitudes avoids a quad across it.
  const ReadMesh band = globe_band(36, -20.0, 40.0, 0.0, 0.0);
  std::vector<Point2> nodes;
  const SourceData source = outline_source(band, "band.ll", "", "--src-crs", &nodes);
  EXPECT_TRUE(source.crs.projected) << source.crs.name;
  ASSERT_EQ(source.polygons.size(), 1u);
  const std::vector<Ring>& annulus = source.polygons[0].rings;
  ASSERT_EQ(annulus.size(), 2u);
  EXPECT_EQ(annulus[0].size(), 36u);  // the 20 S circle round the 40 N one
  EXPECT_EQ(annulus[1].size(), 36u);
  EXPECT_GT(signed_area(annulus[0]), -signed_area(annulus[1]));
  EXPECT_GT(-signed_area(annulus[1]), 0.0);
  ASSERT_EQ(nodes.size(), band.points.size());
  // Every node at its latitude's distance from the North Pole, the projection's centre;
  // `nodes` in the outline's CRS.
  for (std::size_t v = 2; v < nodes.size(); ++v)
    EXPECT_NEAR(std::hypot(nodes[v].x, nodes[v].y), std::hypot(nodes[v % 2].x, nodes[v % 2].y),
                1e-6 * std::hypot(nodes[v].x, nodes[v].y));
}

TEST(MeshOutline, AGridAcrossTheAntimeridianInEitherLongitudes) {
  // Ten quads of 2 degrees from 175 E to 175 W (at 10 S to 5 S), written in [0, 360) (no quad
  // across the cut: the outline is traced in longitudes) and in [-180, 180) (projected first): the
  // same rectangle.
  ReadMesh east = globe_band(180, -10.0, -5.0, 175.0, 0.0),
           west = globe_band(180, -10.0, -5.0, 175.0, -180.0);
  for (ReadMesh* m : {&east, &west}) {  // only the quads from 175 E to 175 W
    m->quads.resize(10);
    m->points.resize(22);
  }
  const SourceData in_degrees = outline_source(east, "east.ll", "", "--src-crs");
  EXPECT_TRUE(in_degrees.crs.geographic);
  ASSERT_EQ(in_degrees.polygons.size(), 1u);
  EXPECT_NEAR(polygon_area(in_degrees.polygons[0]), 100.0, 1e-9);  // 20 x 5 degrees
  const SourceData projected = outline_source(west, "west.ll", "", "--src-crs");
  EXPECT_TRUE(projected.crs.projected);
  ASSERT_EQ(projected.polygons.size(), 1u);
  EXPECT_EQ(projected.polygons[0].rings.size(), 1u);
  // 20 x 5 degrees at 7.5 S: about 2,207 x 553 km on the ground.
  EXPECT_NEAR(polygon_area(projected.polygons[0]) / 1e6, 2207.0 * 553.0, 0.01 * 2207.0 * 553.0);
}

// A grid in metres given as degrees (--src-crs EPSG:4326 for a UTM grid): refused naming
// the node and the option, as polygons are, instead of a projection failing on it.
TEST(MeshOutline, MetresReadAsDegreesAreRefusedNamingTheNode) {
  ReadMesh m = globe_band(180, -10.0, -5.0, 175.0, 0.0);
  m.quads.resize(10);
  m.points.resize(22);
  m.crs = "EPSG:4326";
  for (Point2& p : m.points) p = {500000.0 + 1000.0 * p.x, 5000000.0 + 1000.0 * p.y};
  try {
    outline_source(m, "utm.gr3", "EPSG:4326", "--src-crs");
    FAIL() << "metres taken as degrees";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::crs);
    const std::string what = e.what();
    EXPECT_NE(what.find("'utm.gr3': node 1 "), std::string::npos) << what;
    EXPECT_NE(what.find("are the coordinates in another CRS? Give it with --src-crs"),
              std::string::npos)
        << what;
  }
}

// The defects quality warns of, with the file's node numbers: none in a clean grid; a
// quad given twice (its four sides each of three elements, with the neighbours'), a
// node copied at the same place and used by one quad (a crack), a node in no element, a
// quad that runs round the other way.
TEST(MeshDefects, ElementsTwiceCracksUnusedNodesAndElementsTheOtherWayRound) {
  Grid g = grid(3);
  std::vector<long long> ids;
  for (std::size_t k = 0; k < g.points.size(); ++k) ids.push_back(10 * (k + 1));
  const auto defects = [&] {
    ReadMesh m;
    m.points = g.points;
    m.quads = g.quads;
    m.point_ids = ids;
    return find_mesh_defects(m);
  };
  const MeshDefects clean = defects();
  EXPECT_EQ(clean.num_overused_sides + clean.num_coincident_nodes + clean.num_unused_nodes +
                clean.num_reversed,
            0u);
  EXPECT_TRUE(mesh_defect_warnings(clean).empty());
  std::reverse(g.quads[8].begin(), g.quads[8].end());
  const MeshDefects reversed = defects();
  EXPECT_EQ(reversed.num_reversed, 1u);
  EXPECT_EQ(reversed.num_elements, 9u);
  EXPECT_EQ(reversed.first_reversed, "quad 9");
  ASSERT_EQ(mesh_defect_warnings(reversed).size(), 1u);
  EXPECT_NE(mesh_defect_warnings(reversed)[0].find("1 of its 9 elements run round the other way"),
            std::string::npos);
  std::reverse(g.quads[8].begin(), g.quads[8].end());

  g.quads.push_back(g.quads[4]);    // the middle quad again: nodes 5, 6, 10, 9
  g.points.push_back(g.points[0]);  // node 16, at node 0's place, used by the first quad
  ids.push_back(1000);
  g.quads[0][0] = 16;
  g.points.push_back({7.0, 7.0});  // node 17, in no element
  ids.push_back(2000);
  const MeshDefects d = defects();
  EXPECT_EQ(d.num_overused_sides, 4u);
  EXPECT_EQ(d.first_overused, (std::array<long long, 2>{60, 70}));
  EXPECT_EQ(d.num_coincident_nodes, 1u);  // 16 at 0
  EXPECT_EQ(d.first_coincident, (std::array<long long, 2>{10, 1000}));
  EXPECT_EQ(d.num_unused_nodes, 2u);  // 0 (the grid's corner, its quad now on 16), and 17
  EXPECT_EQ(d.first_unused, 10);
  EXPECT_EQ(d.num_duplicate_elements, 1u);
  EXPECT_EQ(d.first_duplicate, "quad 10 (as quad 5)");
  const std::vector<std::string> w = mesh_defect_warnings(d);
  ASSERT_EQ(w.size(), 4u);
  EXPECT_NE(w[0].find("1 element(s) given twice, on the same nodes (the first: quad 10 (as quad "
                      "5))"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[1].find("4 side(s) of three or more elements (the first between nodes 60 and 70)"),
            std::string::npos)
      << w[1];
  EXPECT_NE(w[2].find("1 node(s) at the place of an earlier one (the first: nodes 10 and 1000"),
            std::string::npos)
      << w[2];
  EXPECT_NE(w[3].find("2 node(s) in no element (the first: node 10)"), std::string::npos) << w[3];
}

// A quad whose opposite sides cross (a bow-tie) and a triangle without area, named by
// the file's numbers; a concave quad is neither.
TEST(MeshDefects, BowTiesAndFlatElements) {
  ReadMesh m;
  m.points = {{0, 0}, {1, 1}, {1, 0}, {0, 1}, {2, 0}, {3, 0}, {5, 5}, {4, 1}, {5, 0}};
  m.quads = {{0, 1, 2, 3}, {5, 8, 6, 7}};  // a bow-tie; an arrowhead, concave at 7
  m.quad_ids = {11, 12};
  m.triangles = {{2, 4, 5}};  // (1,0), (2,0), (3,0): flat
  m.triangle_ids = {13};
  const MeshDefects d = find_mesh_defects(m);
  EXPECT_EQ(d.num_degenerate, 2u);
  EXPECT_EQ(d.first_degenerate, "quad 11");
  const std::vector<std::string> w = mesh_defect_warnings(d);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w[0].find("2 element(s) without area or crossing themselves (the first: quad 11)"),
            std::string::npos)
      << w[0];
  EXPECT_EQ(d.num_duplicate_elements, 0u);
}

// Elements given twice, on the same nodes in any order: counted, the first copy named
// with its original by the file's numbers; a quad and a triangle on three of its nodes
// are not copies.
TEST(MeshDefects, ElementsGivenTwice) {
  ReadMesh m;
  m.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0}, {2, 1}};
  m.quads = {{1, 4, 5, 2}, {0, 1, 2, 3}, {2, 3, 0, 1}, {1, 4, 5, 2}};
  m.quad_ids = {21, 22, 23, 24};
  m.triangles = {{0, 1, 2}, {2, 0, 1}};
  m.triangle_ids = {31, 32};
  const MeshDefects d = find_mesh_defects(m);
  EXPECT_EQ(d.num_duplicate_elements, 3u);
  EXPECT_EQ(d.first_duplicate, "quad 23 (as quad 22)");
  const std::vector<std::string> w = mesh_defect_warnings(d);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w[0].find("3 element(s) given twice, on the same nodes (the first: quad 23 (as quad "
                      "22))"),
            std::string::npos)
      << w[0];
}
