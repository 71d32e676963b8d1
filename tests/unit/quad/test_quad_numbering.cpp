// The mesh's final numbering (quad/quad_numbering.h): reverse Cuthill-McKee over the
// quads' sides, the quads after their vertices, every vertex-indexed array carried along.
#include "quad/quad_numbering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <set>

using namespace isoquad;

namespace {

// An nx x ny grid of unit quads at x offset `x0`, its vertices numbered in a shuffled
// order; boundary vertices on chain `chain`, their arc their x + y, corners fixed.
void add_shuffled_grid(QuadMesh& m, int nx, int ny, double x0, int chain, unsigned seed) {
  const int first = static_cast<int>(m.points.size());
  const int nv = (nx + 1) * (ny + 1);
  std::vector<int> slot(nv);
  std::iota(slot.begin(), slot.end(), first);
  std::mt19937 rng(seed);
  std::shuffle(slot.begin(), slot.end(), rng);
  m.points.resize(first + nv);
  m.chain.resize(first + nv);
  m.arc_m.resize(first + nv);
  m.fixed.resize(first + nv);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int v = slot[j * (nx + 1) + i];
      const bool boundary = i == 0 || j == 0 || i == nx || j == ny;
      m.points[v] = {x0 + i, static_cast<double>(j)};
      m.chain[v] = boundary ? chain : -1;
      m.arc_m[v] = boundary ? x0 + i + j : 0.0;
      m.fixed[v] = (i == 0 || i == nx) && (j == 0 || j == ny);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i;
      m.quads.push_back({slot[a], slot[a + 1], slot[a + nx + 2], slot[a + nx + 1]});
    }
}

// Each quad as its four points, in its own order from its first vertex.
std::multiset<std::array<double, 8>> quads_as_points(const QuadMesh& m) {
  std::multiset<std::array<double, 8>> out;
  for (const auto& q : m.quads) {
    std::array<double, 8> c{};
    for (int k = 0; k < 4; ++k) c[2 * k] = m.points[q[k]].x, c[2 * k + 1] = m.points[q[k]].y;
    out.insert(c);
  }
  return out;
}

}  // namespace

TEST(QuadNumbering, NeighboursAreNumberedCloseTogether) {
  QuadMesh m;
  add_shuffled_grid(m, 60, 20, 0.0, 0, 1);
  add_shuffled_grid(m, 10, 30, 100.0, 1, 2);  // a second part (an island's mesh)
  const QuadMesh before = m;
  EXPECT_GT(vertex_bandwidth(before), 1000);

  const QuadNumbering n = reverse_cuthill_mckee(m);
  // Permutations of the vertices and of the quads.
  std::vector<int> sorted = n.new_vertex;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> ids(m.points.size());
  std::iota(ids.begin(), ids.end(), 0);
  EXPECT_EQ(sorted, ids);
  sorted = n.new_quad;
  std::sort(sorted.begin(), sorted.end());
  ids.resize(m.quads.size());
  std::iota(ids.begin(), ids.end(), 0);
  EXPECT_EQ(sorted, ids);
  // The same mesh gives the same numbers.
  const QuadNumbering again = reverse_cuthill_mckee(m);
  EXPECT_EQ(again.new_vertex, n.new_vertex);
  EXPECT_EQ(again.new_quad, n.new_quad);

  std::vector<int> path = {5, 17, 300, -1};  // an embedded line's vertices (and a gap)
  renumber(m, n, {&path});
  // Cuthill-McKee's levels run across the narrow way: a grid 21 or 11 vertices across
  // has a bandwidth of about that (21 here), against 1,000s shuffled.
  EXPECT_LE(vertex_bandwidth(m), 25) << vertex_bandwidth(m);
  // The same quads, each from the same first vertex, counter-clockwise as before.
  EXPECT_EQ(quads_as_points(m), quads_as_points(before));
  // Every vertex array moved with its vertex.
  for (std::size_t v = 0; v < before.points.size(); ++v) {
    const int w = n.new_vertex[v];
    EXPECT_EQ(m.points[w].x, before.points[v].x);
    EXPECT_EQ(m.points[w].y, before.points[v].y);
    EXPECT_EQ(m.chain[w], before.chain[v]);
    EXPECT_EQ(m.arc_m[w], before.arc_m[v]);
    EXPECT_EQ(m.fixed[w], before.fixed[v]);
  }
  const int old_path[3] = {5, 17, 300};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m.points[path[k]].x, before.points[old_path[k]].x);
    EXPECT_EQ(m.points[path[k]].y, before.points[old_path[k]].y);
  }
  EXPECT_EQ(path[3], -1);
  // The quads in the order of their smallest vertex.
  int last = -1;
  for (const auto& q : m.quads) {
    const int lowest = *std::min_element(q.begin(), q.end());
    EXPECT_GE(lowest, last);
    last = lowest;
  }
  // Each part numbered in one run: its vertices' numbers are consecutive.
  int lo[2] = {1 << 30, 1 << 30}, hi[2] = {-1, -1}, count[2] = {0, 0};
  for (std::size_t w = 0; w < m.points.size(); ++w) {
    const int part = m.points[w].x >= 100.0 ? 1 : 0;
    lo[part] = std::min(lo[part], static_cast<int>(w));
    hi[part] = std::max(hi[part], static_cast<int>(w));
    ++count[part];
  }
  for (int part = 0; part < 2; ++part) EXPECT_EQ(hi[part] - lo[part] + 1, count[part]) << part;
}
