// Butterfly removal (paper, section 2.5): hand-made labellings of square background
// meshes, the mean value map it relies on, and the butterfly step of real tilings
// (square with constant size, France).
#include "tiling/butterflies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/fields_job.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"
#include "mesh/boundary_corners.h"
#include "support/test_support.h"
#include "tiling/build_tiling.h"
#include "tiling/mean_value.h"
#include "tiling/meta_graph.h"
#include "tiling/tiling.h"
#include "unit/mesh/test_domains.h"
#include "unit/tiling/tiling_fixtures.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

BackgroundMesh square_mesh(double side_m, double max_edge_m) {
  BackgroundMeshParams p;
  p.max_edge_m = [max_edge_m](const Point2&) { return max_edge_m; };
  return build_background_mesh(square_domain(side_m), p);
}

BackgroundMesh rectangle_mesh(double width_m, double height_m, double max_edge_m) {
  Domain d;
  d.polygons.push_back({{{0, 0}, {width_m, 0}, {width_m, height_m}, {0, height_m}}, {}});
  BackgroundMeshParams p;
  p.max_edge_m = [max_edge_m](const Point2&) { return max_edge_m; };
  return build_background_mesh(d, p);
}

SizingField constant_size(const BackgroundMesh& m, double h_m) {
  SizingField s;
  s.size_m.assign(m.points.size(), h_m);
  return s;
}

// Labels every triangle by the tile of its centroid; each tile's generator is its
// triangle nearest the tile's centroid.
Tiling tiling_by(const BackgroundMesh& m, int num_tiles,
                 const std::function<int(const Point2&)>& tile_of) {
  Tiling t;
  t.label.resize(m.triangles.size());
  std::vector<double> sx(num_tiles, 0.0), sy(num_tiles, 0.0), n(num_tiles, 0.0);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const Point2 c = centroid(m, static_cast<int>(f));
    t.label[f] = tile_of(c);
    sx[t.label[f]] += c.x;
    sy[t.label[f]] += c.y;
    n[t.label[f]] += 1.0;
  }
  t.generator.assign(num_tiles, -1);
  std::vector<double> best(num_tiles, 1e300);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const int k = t.label[f];
    const double d = distance(centroid(m, static_cast<int>(f)), {sx[k] / n[k], sy[k] / n[k]});
    if (d < best[k]) {
      best[k] = d;
      t.generator[k] = static_cast<int>(f);
    }
  }
  return t;
}

// Background vertex -> number of tiles, for every meta-vertex.
std::map<int, int> meta_vertex_tiles(const MetaGraph& g) {
  std::map<int, int> out;
  for (std::size_t m = 0; m < g.vertices.size(); ++m) out[g.vertices[m]] = g.vertex_num_tiles[m];
  return out;
}

// Interior meta-vertices (background ids) with `num_tiles` tiles.
std::vector<int> interior_meta_vertices(const MetaGraph& g, int num_tiles) {
  std::vector<int> out;
  for (std::size_t m = 0; m < g.vertices.size(); ++m)
    if (!g.vertex_on_boundary[m] && g.vertex_num_tiles[m] == num_tiles)
      out.push_back(g.vertices[m]);
  return out;
}

// The meta-vertices (background ids) of tile t.
std::set<int> tile_meta_vertices(const MetaGraph& g, int t) {
  std::set<int> out;
  for (int m : g.tiles[t].vertices) out.insert(g.vertices[m]);
  return out;
}

// What every successful removal must give: the tiling invariants, the two inner
// meta-vertices replaced by one of 4 tiles, every other meta-vertex kept with its tiles,
// every tile keeping its meta-vertices but the two inner ones, labels outside the four
// tiles untouched, generators inside their tiles.
void expect_one_butterfly_removed(const BackgroundMesh& mesh, const Tiling& before,
                                  const Tiling& after, const ButterflyStats& stats,
                                  const ButterflyParams& params) {
  EXPECT_EQ(stats.found, 1);
  EXPECT_EQ(stats.removed, 1);
  const MetaGraph g0 = build_meta_graph(mesh, before, params.graph);
  const MetaGraph g1 = build_meta_graph(mesh, after, params.graph);
  EXPECT_EQ(check_tiling(mesh, after, g1), "");
  const TilingStats s0 = tiling_stats(g0), s1 = tiling_stats(g1);
  EXPECT_EQ(s1.num_irregular_interior, s0.num_irregular_interior - 2);

  // The two inner meta-vertices lose their status (or become the centre); exactly one
  // meta-vertex of 4 tiles appears; every other keeps its tiles.
  const std::map<int, int> m0 = meta_vertex_tiles(g0), m1 = meta_vertex_tiles(g1);
  std::vector<int> gone, added;
  for (const auto& [v, n] : m0) {
    const auto it = m1.find(v);
    if (it != m1.end() && it->second == n) continue;
    gone.push_back(v);
    EXPECT_EQ(n, 3) << "meta-vertex " << format_point(mesh.points[v]);
    EXPECT_EQ(mesh.boundary_chain_of_vertex[v], -1);
  }
  for (const auto& [v, n] : m1) {
    const auto it = m0.find(v);
    if (it != m0.end() && it->second == n) continue;
    added.push_back(v);
    EXPECT_EQ(n, 4);
  }
  EXPECT_EQ(gone.size(), 2u);
  EXPECT_EQ(added.size(), 1u);

  std::set<int> changed;
  for (std::size_t f = 0; f < before.label.size(); ++f)
    if (before.label[f] != after.label[f]) {
      changed.insert(before.label[f]);
      changed.insert(after.label[f]);
    }
  EXPECT_LE(changed.size(), 4u);
  for (int t = 0; t < before.num_tiles(); ++t) {
    std::set<int> kept = tile_meta_vertices(g0, t);
    for (int v : gone) kept.erase(v);
    const std::set<int> now = tile_meta_vertices(g1, t);
    for (int v : kept) EXPECT_TRUE(now.count(v)) << "tile " << t << " lost a meta-vertex";
    if (!changed.count(t)) {
      EXPECT_EQ(now, tile_meta_vertices(g0, t));
    }
    EXPECT_EQ(after.label[after.generator[t]], t);
  }
}

// Two tiles below y = 5 split at x = 5 - eps, two above split at x = 5 + eps: the triple
// points (5 -/+ eps, 5) are joined by a horizontal meta-edge of length about 2 eps.
int jog_tile(const Point2& c, double eps) {
  if (c.y < 5.0) return c.x < 5.0 - eps ? 0 : 1;
  return c.x < 5.0 + eps ? 2 : 3;
}

// Running bond: three rows of bricks 5 m high on [0, 20] x [0, 15]. Rows meet in
// T-junctions at least 2.5 m apart, except the junctions (10, 5) and (10.6, 5): the one
// butterfly.
int brick_tile(const Point2& c) {
  static const std::vector<std::vector<double>> kJoints{
      {5.0, 10.0, 15.0}, {2.5, 7.5, 10.6, 17.5}, {5.0, 13.5}};
  const int row = c.y < 5.0 ? 0 : c.y < 10.0 ? 1 : 2;
  int tile = 0;
  for (int r = 0; r < row; ++r) tile += static_cast<int>(kJoints[r].size()) + 1;
  for (double x : kJoints[row])
    if (c.x > x) ++tile;
  return tile;
}

int grid_tile(const Point2& c) {
  const int col = std::min(3, static_cast<int>(c.x / 5.0));
  const int row = std::min(3, static_cast<int>(c.y / 5.0));
  return 4 * row + col;
}

}  // namespace

TEST(MeanValue, ReproducesAffineMaps) {
  const BackgroundMesh m = build_background_mesh(disk_domain(3.0, 40), [] {
    BackgroundMeshParams p;
    p.max_edge_m = [](const Point2&) { return 0.3; };
    return p;
  }());
  auto affine = [](const Point2& x) {
    return Point2{0.3 * x.x - 0.7 * x.y + 2.0, 0.2 * x.x + 0.5 * x.y - 1.0};
  };
  std::vector<char> fixed(m.points.size(), 0);
  std::vector<Point2> uv(m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v)
    if (m.boundary_chain_of_vertex[v] >= 0) {
      fixed[v] = 1;
      uv[v] = affine(m.points[v]);
    }
  ASSERT_TRUE(mean_value_parameterization(m.points, m.triangles, fixed, uv));
  double worst = 0.0;
  for (std::size_t v = 0; v < m.points.size(); ++v)
    worst = std::max(worst, distance(uv[v], affine(m.points[v])));
  // The systems are solved to a relative residual of 1e-9 (measured error 3e-8 here);
  // wrong weights miss by orders of magnitude more.
  EXPECT_LT(worst, 1e-6);
}

TEST(MeanValue, ConvexBoundaryGivesAOneToOneMap) {
  // An L-shaped (non-convex) region mapped onto a circle: every triangle keeps its
  // orientation.
  BackgroundMeshParams p;
  p.max_edge_m = [](const Point2&) { return 0.25; };
  const BackgroundMesh m = build_background_mesh(l_domain(2.0), p);
  ASSERT_EQ(m.chains.size(), 1u);
  const BoundaryChain& chain = m.chains[0];
  std::vector<char> fixed(m.points.size(), 0);
  std::vector<Point2> uv(m.points.size());
  for (std::size_t k = 0; k < chain.vertices.size(); ++k) {
    const double a = 2.0 * kPi * chain.arc_length_m[k] / chain.length_m;
    fixed[chain.vertices[k]] = 1;
    uv[chain.vertices[k]] = {std::cos(a), std::sin(a)};
  }
  ASSERT_TRUE(mean_value_parameterization(m.points, m.triangles, fixed, uv));
  int flipped = 0;
  for (const auto& t : m.triangles) {
    const Point2 &a = uv[t[0]], &b = uv[t[1]], &c = uv[t[2]];
    if ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) <= 0.0) ++flipped;
  }
  EXPECT_EQ(flipped, 0);
}

TEST(Butterflies, TwoTriplePointsBecomeOneDegreeFourMetaVertex) {
  const BackgroundMesh mesh = square_mesh(10.0, 0.25);
  const SizingField size = constant_size(mesh, 2.5);  // tiles 2h = 5 m, threshold 1.25 m
  const Tiling before = tiling_by(mesh, 4, [](const Point2& c) { return jog_tile(c, 0.3); });
  const ButterflyParams params;
  const MetaGraph g0 = build_meta_graph(mesh, before, params.graph);
  ASSERT_EQ(check_tiling(mesh, before, g0), "");
  ASSERT_EQ(interior_meta_vertices(g0, 3).size(), 2u);
  EXPECT_EQ(tiling_stats(g0).share_quads, 0.5);  // tiles 1 and 2 are pentagons

  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, params);
  expect_one_butterfly_removed(mesh, before, after, stats, params);
  const MetaGraph g1 = build_meta_graph(mesh, after, params.graph);
  const std::vector<int> centre = interior_meta_vertices(g1, 4);
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_LT(distance(mesh.points[centre[0]], {5.0, 5.0}), 1.0);
  EXPECT_EQ(tiling_stats(g1).share_quads, 1.0);
  EXPECT_EQ(tiling_stats(g1).num_irregular_interior, 0);
}

TEST(Butterflies, OneButterflyInARunningBond) {
  const BackgroundMesh mesh = rectangle_mesh(20.0, 15.0, 0.25);
  const SizingField size = constant_size(mesh, 2.5);
  const Tiling before = tiling_by(mesh, 12, brick_tile);
  const ButterflyParams params;
  const MetaGraph g0 = build_meta_graph(mesh, before, params.graph);
  ASSERT_EQ(check_tiling(mesh, before, g0), "");
  ASSERT_EQ(interior_meta_vertices(g0, 3).size(), 13u);  // T-junctions only
  ASSERT_TRUE(interior_meta_vertices(g0, 4).empty());

  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, params);
  expect_one_butterfly_removed(mesh, before, after, stats, params);
  const MetaGraph g1 = build_meta_graph(mesh, after, params.graph);
  const std::vector<int> centre = interior_meta_vertices(g1, 4);
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_LT(distance(mesh.points[centre[0]], {10.3, 5.0}), 1.0);
  EXPECT_EQ(interior_meta_vertices(g1, 3).size(), 11u);
  // The two tiles along the inner meta-edge were pentagons and become quadrangles.
  EXPECT_GT(tiling_stats(g1).share_quads, tiling_stats(g0).share_quads);
}

TEST(Butterflies, GridCrossingsSplitByTheBackgroundMeshAreAllRepaired) {
  // A 4 x 4 grid labelled by centroid: where the jagged tile boundaries cross, a grid
  // vertex often splits into two triple points one background edge apart.
  const BackgroundMesh mesh = square_mesh(20.0, 0.3);
  const SizingField size = constant_size(mesh, 2.5);
  const Tiling before = tiling_by(mesh, 16, grid_tile);
  const ButterflyParams params;
  const MetaGraph g0 = build_meta_graph(mesh, before, params.graph);
  ASSERT_EQ(check_tiling(mesh, before, g0), "");
  const TilingStats s0 = tiling_stats(g0);

  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, params);
  const MetaGraph g1 = build_meta_graph(mesh, after, params.graph);
  EXPECT_EQ(check_tiling(mesh, after, g1), "");
  const TilingStats s1 = tiling_stats(g1);
  std::printf("grid: %d split crossings found, %d removed\n", stats.found, stats.removed);
  EXPECT_EQ(stats.found, s0.num_irregular_interior / 2);
  EXPECT_EQ(stats.removed, stats.found);
  EXPECT_EQ(s1.num_irregular_interior, 0);
  EXPECT_EQ(s1.share_quads, 1.0);
  EXPECT_EQ(interior_meta_vertices(g1, 4).size(), 9u);

  // Deterministic.
  Tiling again = before;
  const ButterflyStats stats2 = remove_butterflies(mesh, size, again, params);
  EXPECT_EQ(stats2.found, stats.found);
  EXPECT_EQ(stats2.removed, stats.removed);
  EXPECT_EQ(again.label, after.label);
  EXPECT_EQ(again.generator, after.generator);
}

TEST(Butterflies, LongInnerMetaEdgeIsNotAButterfly) {
  const BackgroundMesh mesh = square_mesh(10.0, 0.25);
  const SizingField size = constant_size(mesh, 2.5);
  const Tiling before = tiling_by(mesh, 4, [](const Point2& c) { return jog_tile(c, 1.5); });
  ButterflyParams params;
  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, params);
  EXPECT_EQ(stats.found, 0);
  EXPECT_EQ(stats.removed, 0);
  EXPECT_EQ(after.label, before.label);

  // The threshold decides: with 2 h instead of h / 2 the same meta-edge is short.
  params.max_length_ratio = 2.0;
  const ButterflyStats relaxed = remove_butterflies(mesh, size, after, params);
  expect_one_butterfly_removed(mesh, before, after, relaxed, params);
}

TEST(Butterflies, TriplePointNearTheDomainBoundaryIsNotAButterfly) {
  // Three tiles meeting 0.4 m from the boundary: the short meta-edge ends on the
  // boundary, so it joins no two interior degree-3 meta-vertices.
  const BackgroundMesh mesh = square_mesh(10.0, 0.25);
  const SizingField size = constant_size(mesh, 2.5);
  const Tiling before = tiling_by(mesh, 3, [](const Point2& c) {
    return c.x < 5.0 ? 0 : c.y < 0.4 ? 1 : 2;
  });
  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, ButterflyParams());
  EXPECT_EQ(stats.found, 0);
  EXPECT_EQ(after.label, before.label);
}

TEST(Butterflies, DegreeFourEndsAreNotAButterfly) {
  // Four quadrants around a background vertex c, and a thin row of tiles between y = c.y
  // and y = c'.y, c' a background vertex about 0.6 m above: two crossings of 4 tiles
  // joined by a short meta-edge. Both crossings must be single background vertices, so
  // c and c' are chosen among the vertices near the ideal positions until they are.
  const BackgroundMesh mesh = square_mesh(10.0, 0.25);
  const SizingField size = constant_size(mesh, 2.5);
  std::vector<int> near;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (distance(mesh.points[v], {5.0, 5.0}) < 0.5) near.push_back(static_cast<int>(v));
  std::optional<Tiling> found_tiling;
  for (int c : near) {
    for (int d : near) {
      const Point2 a = mesh.points[c], b = mesh.points[d];
      if (b.y - a.y < 0.4 || b.y - a.y > 0.8 || std::abs(b.x - a.x) > 0.1) continue;
      // Left or right of the line through c and c', then below, between or above.
      const Tiling t = tiling_by(mesh, 6, [a, b](const Point2& x) {
        const double side = (b.x - a.x) * (x.y - a.y) - (b.y - a.y) * (x.x - a.x);
        return (side > 0.0 ? 0 : 1) + 2 * (x.y < a.y ? 0 : x.y < b.y ? 1 : 2);
      });
      const MetaGraph g = build_meta_graph(mesh, t);
      if (check_tiling(mesh, t, g).empty() && interior_meta_vertices(g, 4).size() == 2u &&
          interior_meta_vertices(g, 3).empty()) {
        found_tiling = t;
        break;
      }
    }
    if (found_tiling) break;
  }
  ASSERT_TRUE(found_tiling.has_value()) << "no exact pair of crossings near (5, 5)";
  const Tiling before = *found_tiling;
  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, ButterflyParams());
  EXPECT_EQ(stats.found, 0);
  EXPECT_EQ(after.label, before.label);
}

TEST(Butterflies, KeptWhenItWouldTurnTwoQuadrangleTilesIntoTriangles) {
  // Without corner meta-vertices at the square's corners, the two tiles along the inner
  // meta-edge are quadrangles: merging the triple points would make them triangles.
  BackgroundMesh mesh = square_mesh(10.0, 0.25);
  for (BoundaryChain& chain : mesh.chains) {
    std::fill(chain.is_corner.begin(), chain.is_corner.end(), 0);
    std::fill(chain.corner_turning_deg.begin(), chain.corner_turning_deg.end(), 0.0);
  }
  const SizingField size = constant_size(mesh, 2.5);
  const Tiling before = tiling_by(mesh, 4, [](const Point2& c) { return jog_tile(c, 0.3); });
  ButterflyParams params;
  Tiling after = before;
  const ButterflyStats stats = remove_butterflies(mesh, size, after, params);
  EXPECT_EQ(stats.found, 1);
  EXPECT_EQ(stats.removed, 0);
  EXPECT_EQ(after.label, before.label);
}

namespace {

const TilingStepReport& step_named(const TilingResult& r, const std::string& name) {
  const auto it = std::find_if(r.steps.begin(), r.steps.end(),
                               [&](const TilingStepReport& s) { return s.step == name; });
  EXPECT_NE(it, r.steps.end()) << "no step " << name;
  return it != r.steps.end() ? *it : r.steps.back();
}

// What the butterfly step of a real tiling must give, whatever the earlier steps did.
void expect_butterfly_step_improves(const BackgroundMesh& mesh, const TilingResult& r) {
  const TilingStepReport& conform = step_named(r, "conform");
  const TilingStepReport& butterfly = step_named(r, "butterfly");
  EXPECT_EQ(check_tiling(mesh, r.tiling, r.graph), "");
  EXPECT_GT(butterfly.butterflies_found, 0);
  EXPECT_GE(butterfly.butterflies_removed, 0.9 * butterfly.butterflies_found);
  // Each removal turns two degree-3 meta-vertices into one of degree 4; the repairs that
  // close the step (reflex corners) may add back a few.
  EXPECT_LE(butterfly.stats.num_irregular_interior,
            conform.stats.num_irregular_interior - 1.95 * butterfly.butterflies_removed);
  EXPECT_GE(butterfly.stats.share_quads, conform.stats.share_quads);
  std::printf(
      "butterflies: %d found, %d removed, %.2f s; tiles with 4 meta-vertices %.1f%% -> "
      "%.1f%%; irregular interior meta-vertices %d -> %d\n",
      butterfly.butterflies_found, butterfly.butterflies_removed, butterfly.seconds,
      100.0 * conform.stats.share_quads, 100.0 * butterfly.stats.share_quads,
      conform.stats.num_irregular_interior, butterfly.stats.num_irregular_interior);
}

}  // namespace

TEST(ButterfliesOnRealTilings, SquareWithConstantSizeAndAxisAlignedCross) {
  FieldsResult f = fields_on(square_domain(100.0), 2.5, true);
  const TilingResult r = build_tiling(f.mesh, f.size, f.cross, TilingParams());
  expect_butterfly_step_improves(f.mesh, r);
  // The paper's uniform-sizing case (2.6: about 75% quadrangles before subdivision).
  // Measured 1.0 from seeded fronts (0.69 to 0.78 from merging); the issue asks 0.9.
  EXPECT_GE(step_named(r, "butterfly").stats.share_quads, 0.9);
}

TEST(ButterfliesOnRealTilings, France) {
  FieldsOptions o;
  o.front.read.path = sample("france.shp");
  o.sizing.hmax_m = 28000.0;  // about 4,500 quads
  FieldsResult f = build_fields(o);
  tag_corners(f.mesh, f.size, CornerParams());  // as the mesh job does
  const TilingResult r = build_tiling(f.mesh, f.size, f.cross, TilingParams());
  std::printf("France: %zu background triangles\n", f.mesh.triangles.size());
  expect_butterfly_step_improves(f.mesh, r);
  // The tiling the subdivision gets, after the re-splitting of pairs (measured: 79%; the
  // paper reports about 70% after its local parameterizations).
  const double share = step_named(r, "resplit").stats.share_quads;
  std::printf("France: %.1f%% of tiles with 4 meta-vertices after re-splitting\n", 100 * share);
  EXPECT_GE(share, 0.75);
}
