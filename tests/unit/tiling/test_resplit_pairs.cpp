// Re-splitting pairs of tiles (resplit_pairs.h) on real tilings:
// the invariants hold, the mesh the subdivision would make has fewer irregular interior
// vertices, no pair is re-split that should not be, and the step is deterministic.
#include "tiling/resplit_pairs.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "app/fields_job.h"
#include "mesh/boundary_corners.h"
#include "support/test_support.h"
#include "tiling/build_tiling.h"
#include "tiling/meta_graph.h"
#include "unit/mesh/test_domains.h"
#include "unit/tiling/tiling_fixtures.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// Irregular interior vertices of the barycentric subdivision of the tiling: tile centres
// (valence = number of meta-vertices) and interior meta-vertices (valence = tiles), both
// counted by how far they are from 4.
int interior_irregularity(const BackgroundMesh& mesh, const MetaGraph& g) {
  const std::vector<char> boundary = boundary_vertex_flags(mesh);
  int sum = 0;
  for (const TileCycle& t : g.tiles) sum += std::abs(static_cast<int>(t.vertices.size()) - 4);
  for (std::size_t m = 0; m < g.vertices.size(); ++m)
    if (!boundary[g.vertices[m]]) sum += std::abs(g.vertex_num_tiles[m] - 4);
  return sum;
}

struct Case {
  FieldsResult fields;
  TilingResult tiling;  // up to the butterflies
};

Case corsica() {
  Case c;
  FieldsOptions o;
  o.front.read.path = sample("corsica.shp");
  o.sizing.hmax_m = 4000.0;
  c.fields = build_fields(o);
  tag_corners(c.fields.mesh, c.fields.size, CornerParams());
  TilingParams p;
  p.stop_after = TilingStep::butterfly;
  c.tiling = build_tiling(c.fields.mesh, c.fields.size, c.fields.cross, p);
  return c;
}

}  // namespace

TEST(ResplitPairs, CorsicaKeepsInvariantsAndLosesIrregularVertices) {
  Case c = corsica();
  const BackgroundMesh& mesh = c.fields.mesh;
  const MetaGraph& before = c.tiling.graph;
  Tiling tiling = c.tiling.tiling;
  const ResplitStats stats = resplit_pairs(mesh, tiling, ResplitParams());
  const MetaGraph after = build_meta_graph(mesh, tiling);
  EXPECT_EQ(check_tiling(mesh, tiling, after), "");
  const TilingStats sb = tiling_stats(before), sa = tiling_stats(after);
  const int ib = interior_irregularity(mesh, before), ia = interior_irregularity(mesh, after);
  std::printf("Corsica: %d pairs re-split in %d rounds; tiles with 4 meta-vertices %.1f%% -> "
              "%.1f%%; interior irregularity %d -> %d\n",
              stats.resplit, stats.rounds, 100 * sb.share_quads, 100 * sa.share_quads, ib, ia);
  EXPECT_EQ(sa.num_tiles, sb.num_tiles);
  // Measured: 101 pairs, 60% -> 82%, irregularity 407 -> 225.
  EXPECT_GT(stats.resplit, 20);
  // Every re-split leaves a quadrangle, most of them two; a tile next to it may lose a
  // meta-vertex that the union removed.
  EXPECT_GE(sa.share_quads, sb.share_quads + 0.5 * stats.resplit / sb.num_tiles);
  // Each re-split lowers the irregularity, inside or on the boundary; most of it inside.
  EXPECT_LE(ia, ib - stats.resplit / 2);
}

TEST(ResplitPairs, TiesGoToMoreQuadrangleTiles) {
  // A split that keeps the irregularity but leaves more quadrangle tiles is made by
  // default and not without quads_on_ties: more quadrangle tiles, no more irregularity.
  Case c = corsica();
  const BackgroundMesh& mesh = c.fields.mesh;
  Tiling with = c.tiling.tiling, without = c.tiling.tiling;
  ResplitParams p;
  const int num_with = resplit_pairs(mesh, with, p).resplit;
  p.quads_on_ties = false;
  const int num_without = resplit_pairs(mesh, without, p).resplit;
  const MetaGraph gw = build_meta_graph(mesh, with), go = build_meta_graph(mesh, without);
  EXPECT_EQ(check_tiling(mesh, with, gw), "");
  const double qw = tiling_stats(gw).share_quads, qo = tiling_stats(go).share_quads;
  const int iw = interior_irregularity(mesh, gw), io = interior_irregularity(mesh, go);
  std::printf("Corsica: ties taken %d splits, %.1f%% quadrangle tiles, irregularity %d; "
              "not taken %d, %.1f%%, %d\n", num_with, 100 * qw, iw, num_without, 100 * qo, io);
  EXPECT_GT(num_with, num_without);
  EXPECT_GE(qw, qo + 0.02);
  EXPECT_LE(iw, io);
}

TEST(ResplitPairs, SplitsWhoseQuadsWouldNotBeConvexAreRefused) {
  // No quad can have convexity above 1 (the sine of a turn): every split is refused.
  Case c = corsica();
  Tiling tiling = c.tiling.tiling;
  ResplitParams p;
  p.min_subdivision_convexity = 1.01;
  EXPECT_EQ(resplit_pairs(c.fields.mesh, tiling, p).resplit, 0);
  EXPECT_EQ(tiling.label, c.tiling.tiling.label);
  // Demanding strictly convex quads around the centroid keeps fewer splits than the
  // default, which leaves mildly bent ones to smoothing.
  Tiling strict = c.tiling.tiling, loose = c.tiling.tiling;
  p.min_subdivision_convexity = 0.2;
  const int num_strict = resplit_pairs(c.fields.mesh, strict, p).resplit;
  const int num_loose = resplit_pairs(c.fields.mesh, loose, ResplitParams()).resplit;
  EXPECT_LT(num_strict, num_loose);
  EXPECT_GT(num_strict, 0);
}

TEST(ResplitPairs, LeavesAQuadrangleLatticeAlone) {
  // The square with constant size and axis-aligned cross: every tile is a quadrangle
  // after the butterflies, so no pair may change.
  FieldsResult f = fields_on(square_domain(100.0), 2.5, true);
  TilingParams p;
  p.stop_after = TilingStep::butterfly;
  const TilingResult r = build_tiling(f.mesh, f.size, f.cross, p);
  ASSERT_EQ(tiling_stats(r.graph).share_quads, 1.0);
  Tiling tiling = r.tiling;
  const ResplitStats stats = resplit_pairs(f.mesh, tiling, ResplitParams());
  EXPECT_EQ(stats.resplit, 0);
  EXPECT_EQ(tiling.label, r.tiling.label);
}

TEST(ResplitPairs, SameTilingGivesTheSameLabels) {
  Case c = corsica();
  Tiling a = c.tiling.tiling, b = c.tiling.tiling;
  resplit_pairs(c.fields.mesh, a, ResplitParams());
  resplit_pairs(c.fields.mesh, b, ResplitParams());
  EXPECT_EQ(a.label, b.label);
  EXPECT_EQ(a.generator, b.generator);
}
