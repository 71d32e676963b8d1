// mesh_outline on small grids: holes, holes and parts touching at a node, clockwise
// files, triangles beside quadrangles, and the meshes whose boundary is not loops.
#include <gtest/gtest.h>

#include <algorithm>

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
