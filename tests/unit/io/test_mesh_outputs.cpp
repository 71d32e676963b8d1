// The mesh writers on a small hand-made mesh (a 3 x 3 grid of 1 km quads in UTM 31N with
// the middle quad missing: one island; its south side on the "open" ring): boundary
// loops and kinds, SCHISM gr3 against a golden file and a parser of its own, Gmsh files
// read back by the gmsh binary, legacy VTK by meshio, UGRID by python3-netcdf4, and the
// all-or-nothing writing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "gis/atomic_output.h"
#include "gis/crs.h"
#include "gis/read_mesh.h"
#include "io/mesh_boundary.h"
#include "io/write_mesh.h"
#include "io/write_vtu.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

constexpr double kX0 = 500000, kY0 = 5000000, kStep = 1000;

struct Fixture {
  QuadMesh mesh;
  QuadMetrics metrics;
  std::string crs_wkt = parse_crs("EPSG:32631", "test").wkt;
  // A closed polyline (its first point repeated) round the mesh's bottom side.
  std::vector<Point2> open_ring{{kX0 - 1000, kY0},
                                {kX0 + 4000, kY0},
                                {kX0 + 4000, kY0 - 9000},
                                {kX0 - 1000, kY0 - 9000},
                                {kX0 - 1000, kY0}};

  Fixture() {
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) mesh.points.push_back({kX0 + kStep * i, kY0 + kStep * j});
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        if (i != 1 || j != 1) {
          const int a = j * 4 + i;
          mesh.quads.push_back({a, a + 1, a + 5, a + 4});
        }
    mesh.chain.assign(mesh.points.size(), -1);
    mesh.arc_m.assign(mesh.points.size(), 0.0);
    mesh.fixed.assign(mesh.points.size(), 0);
    const std::size_t nq = mesh.quads.size();
    for (std::size_t q = 0; q < nq; ++q) {
      metrics.size_ratio.push_back(1.0 + 0.01 * q);
      metrics.orientation_deg.push_back(0.5 * q);
      metrics.min_angle_deg.push_back(90);
      metrics.max_angle_deg.push_back(90);
      metrics.aspect_ratio.push_back(1.0 + 0.1 * q);
      metrics.eta.push_back(1);
      metrics.orthogonality.push_back(0.02 * q);
    }
    metrics.degree.assign(mesh.points.size(), 0);
    for (const auto& q : mesh.quads)
      for (int v : q) ++metrics.degree[v];
    metrics.boundary.assign(mesh.points.size(), 1);
    metrics.ideal_degree = metrics.degree;
    metrics.irregular_corners.assign(nq, 0.0);
  }

  MeshOutputData data(bool with_depth = true) const {
    MeshOutputData d;
    d.mesh = &mesh;
    d.metrics = &metrics;
    d.crs_wkt = crs_wkt;
    d.boundary = extract_boundary(mesh, PolylineIndex({open_ring}), 1.0);
    if (with_depth)
      for (std::size_t i = 0; i < mesh.points.size(); ++i) d.depth.push_back(10.0 + 0.5 * i);
    d.command_line = "isoquad mesh test";
    d.quality = {{"num_quads", "8"}};
    return d;
  }
};

std::string golden(const std::string& name) {
  return std::string(ISOQUAD_SOURCE_DIR) + "/tests/formats/" + name;
}

// A SCHISM hgrid parser of our own: nodes, elements, boundary segments.
struct Gr3 {
  std::vector<std::array<double, 3>> nodes;       // x, y, depth
  std::vector<std::vector<int>> elements;         // 1-based node ids
  std::vector<std::vector<int>> open;             // node ids per open segment
  std::vector<std::pair<int, std::vector<int>>> land;  // flag, node ids
};

Gr3 parse_gr3(const std::string& text) {
  std::istringstream in(text);
  Gr3 g;
  std::string line;
  std::getline(in, line);  // comment
  std::size_t ne = 0, np = 0;
  in >> ne >> np;
  for (std::size_t i = 0; i < np; ++i) {
    std::size_t id = 0;
    std::array<double, 3> n{};
    in >> id >> n[0] >> n[1] >> n[2];
    EXPECT_EQ(id, i + 1);
    g.nodes.push_back(n);
  }
  for (std::size_t e = 0; e < ne; ++e) {
    std::size_t id = 0;
    int k = 0;
    in >> id >> k;
    EXPECT_EQ(id, e + 1);
    std::vector<int> el(k);
    for (int& v : el) in >> v;
    g.elements.push_back(el);
  }
  auto count_line = [&in](const std::string& label, int* flag = nullptr) {
    std::size_t n = 0;
    in >> n;
    if (flag) in >> *flag;
    std::string rest;
    std::getline(in, rest);
    EXPECT_NE(rest.find(label), std::string::npos) << rest;
    return n;
  };
  const std::size_t nopen = count_line("Number of open boundaries");
  const std::size_t total_open = count_line("Total number of open boundary nodes");
  std::size_t seen = 0;
  for (std::size_t k = 0; k < nopen; ++k) {
    std::vector<int> seg(count_line("Number of nodes for open boundary"));
    for (int& v : seg) in >> v;
    seen += seg.size();
    g.open.push_back(seg);
  }
  EXPECT_EQ(seen, total_open);
  const std::size_t nland = count_line("Number of land boundaries");
  const std::size_t total_land = count_line("Total number of land boundary nodes");
  seen = 0;
  for (std::size_t k = 0; k < nland; ++k) {
    int flag = -1;
    std::vector<int> seg(count_line("Number of nodes for land boundary", &flag));
    for (int& v : seg) in >> v;
    seen += seg.size();
    g.land.push_back({flag, seg});
  }
  EXPECT_EQ(seen, total_land);
  EXPECT_TRUE(in.good() || in.eof());
  return g;
}


}  // namespace

TEST(MeshBoundary, LoopsKindsAndSegments) {
  const Fixture f;
  const MeshBoundary b = extract_boundary(f.mesh, PolylineIndex({f.open_ring}), 1.0);
  ASSERT_EQ(b.loops.size(), 2u);
  EXPECT_EQ(b.loops[0], (std::vector<int>{0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4}));
  EXPECT_EQ(b.loops[1].size(), 4u);
  EXPECT_EQ(b.num_open_edges, 3u);
  EXPECT_EQ(b.num_land_edges, 9u + 4u);
  ASSERT_EQ(b.segments.size(), 3u);
  EXPECT_EQ(b.segments[0].kind, BoundaryKind::open);
  EXPECT_EQ(b.segments[0].nodes, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_FALSE(b.segments[0].closed);
  EXPECT_EQ(b.segments[1].kind, BoundaryKind::land);
  EXPECT_EQ(b.segments[1].nodes, (std::vector<int>{3, 7, 11, 15, 14, 13, 12, 8, 4, 0}));
  EXPECT_FALSE(b.segments[1].island);
  EXPECT_EQ(b.segments[2].kind, BoundaryKind::land);
  EXPECT_TRUE(b.segments[2].closed);
  EXPECT_TRUE(b.segments[2].island);  // the hole runs clockwise
  EXPECT_EQ(std::set<int>(b.segments[2].nodes.begin(), b.segments[2].nodes.end()),
            (std::set<int>{5, 6, 9, 10}));

  // Without lines everything is land; a ring too far away (tolerance) changes nothing.
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex(), 1.0).num_open_edges, 0u);
  std::vector<Point2> shifted = f.open_ring;
  for (Point2& p : shifted) p.y -= 5.0;
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({shifted}), 1.0).num_open_edges, 0u);
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({shifted}), 6.0).num_open_edges, 3u);
}

TEST(MeshBoundary, OpenPolylinesMarkOnlyTheEdgesAlongThem) {
  // Two open lines (not rings): one along the left side from the bottom corner to
  // halfway up the mesh, one along the top side's middle edge. Only the edges with both
  // ends and the midpoint on a line are open; the vertices at the lines' ends start and
  // end the open segments, and the corner between the two lines' sides stays land.
  const Fixture f;
  const std::vector<Point2> left{{kX0, kY0 + 0.3}, {kX0, kY0 + 2 * kStep}};
  const std::vector<Point2> top{{kX0 + kStep, kY0 + 3 * kStep}, {kX0 + 2 * kStep, kY0 + 3 * kStep}};
  const MeshBoundary b = extract_boundary(f.mesh, PolylineIndex({left, top}), 1.0);
  EXPECT_EQ(b.num_open_edges, 3u);
  EXPECT_EQ(b.num_land_edges, 9u + 4u);
  std::vector<std::vector<int>> open;
  for (const BoundarySegment& s : b.segments)
    if (s.kind == BoundaryKind::open) open.push_back(s.nodes);
  std::sort(open.begin(), open.end());
  // Counter-clockwise round the domain: down the left side (8 -> 4 -> 0), and along the
  // top from right to left (14 -> 13).
  EXPECT_EQ(open, (std::vector<std::vector<int>>{{8, 4, 0}, {14, 13}}));
  // A hole's edge lies on no line: the island stays land.
  for (const BoundarySegment& s : b.segments) {
    if (s.island) {
      EXPECT_EQ(s.kind, BoundaryKind::land);
    }
  }
}

TEST(MeshBoundary, AnEdgeAcrossACornerOfTheLinesIsOpenWithItsChordShare) {
  // A line through the bottom side's first edge (0 -> 1, 1 km) that bends 150 m away
  // at the edge's middle (a corner turning by 33 degrees): the edge's midpoint lies
  // 150 m off, so it is open only when the chord share allows 15% of its length.
  const Fixture f;
  const std::vector<Point2> bent{
      {kX0 - 1, kY0}, {kX0 + 0.5 * kStep, kY0 - 150}, {kX0 + kStep + 1, kY0}};
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({bent}), 1.0).num_open_edges, 0u);
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({bent}), 1.0, 0.2).num_open_edges, 1u);
  // A line's slack widens its own tolerance only.
  const std::vector<Point2> below{{kX0, kY0 - 20}, {kX0 + 3 * kStep, kY0 - 20}};
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({below, bent}, {25.0, 0.0}), 1.0).num_open_edges,
            3u);
  EXPECT_EQ(extract_boundary(f.mesh, PolylineIndex({below, bent}, {0.0, 25.0}), 1.0).num_open_edges,
            0u);
}

// Each boundary edge of the gr3's elements, once, as its segments cover them (an
// island's land segment, flag 1, closed by its last edge), or a failure.
void expect_segments_cover_the_boundary(const Gr3& g) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& el : g.elements)
    for (std::size_t k = 0; k < el.size(); ++k)
      ++edges[{std::min(el[k], el[(k + 1) % el.size()]), std::max(el[k], el[(k + 1) % el.size()])}];
  std::set<std::pair<int, int>> boundary, covered;
  for (const auto& [e, n] : edges)
    if (n == 1) boundary.insert(e);
  auto cover = [&covered](const std::vector<int>& s, bool closed) {
    for (std::size_t i = 0; i + 1 < s.size() + (closed ? 1 : 0); ++i) {
      const int a = s[i], b = s[(i + 1) % s.size()];
      EXPECT_TRUE(covered.insert({std::min(a, b), std::max(a, b)}).second) << a << "-" << b;
    }
  };
  for (const auto& s : g.open) {
    EXPECT_NE(s.front(), s.back()) << "SCHISM stops on a looped open boundary";
    cover(s, false);
  }
  for (const auto& [flag, s] : g.land) cover(s, flag == 1);
  EXPECT_EQ(covered, boundary);
}

TEST(MeshOutputs, Gr3MatchesGoldenAndParses) {
  const Fixture f;
  TempDir dir;
  const std::string gr3 = dir.file("hgrid.gr3");
  write_mesh_outputs(f.data(), {{gr3, "", false}});
  ASSERT_TRUE(std::filesystem::exists(dir.file("hgrid.ll")));
  const std::string text = read_file(gr3);
  if (std::getenv("ISOQUAD_UPDATE_GOLDEN")) {
    write_file(golden("hgrid.gr3"), text);
    write_file(golden("hgrid.ll"), read_file(dir.file("hgrid.ll")));
  }
  EXPECT_EQ(text, read_file(golden("hgrid.gr3")));

  const Gr3 g = parse_gr3(text);
  ASSERT_EQ(g.nodes.size(), 16u);
  ASSERT_EQ(g.elements.size(), 8u);
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    EXPECT_DOUBLE_EQ(g.nodes[i][0], f.mesh.points[i].x);
    EXPECT_DOUBLE_EQ(g.nodes[i][1], f.mesh.points[i].y);
    EXPECT_DOUBLE_EQ(g.nodes[i][2], 10.0 + 0.5 * i);  // depth, positive down
  }
  for (std::size_t e = 0; e < g.elements.size(); ++e) {
    ASSERT_EQ(g.elements[e].size(), 4u);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(g.elements[e][k], f.mesh.quads[e][k] + 1);
  }
  ASSERT_EQ(g.open.size(), 1u);
  for (int n : g.open[0]) EXPECT_EQ(g.nodes[n - 1][1], kY0);  // on the south side
  ASSERT_EQ(g.land.size(), 2u);
  EXPECT_EQ(g.land[0].first, 0);  // exterior
  EXPECT_EQ(g.land[1].first, 1);  // island
  // The segments' edges are exactly the mesh's boundary edges.
  expect_segments_cover_the_boundary(g);

  // hgrid.ll: the same nodes in lon/lat (UTM 31N is centred on 3 E).
  const Gr3 ll = parse_gr3(read_file(dir.file("hgrid.ll")));
  const Gr3 ll_golden = parse_gr3(read_file(golden("hgrid.ll")));
  ASSERT_EQ(ll.nodes.size(), 16u);
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_NEAR(ll.nodes[i][0], ll_golden.nodes[i][0], 1e-9);
    EXPECT_NEAR(ll.nodes[i][1], ll_golden.nodes[i][1], 1e-9);
    EXPECT_NEAR(ll.nodes[i][0], 3.0 + 0.01272 * (i % 4), 0.0005);
    EXPECT_NEAR(ll.nodes[i][1], 45.1, 0.1);
  }
  EXPECT_EQ(ll.elements, g.elements);
  EXPECT_EQ(ll.open, g.open);
}

// A whole loop of the exterior boundary, open (a box of sea) or land (a lake), is two
// segments that share their ends, as SCHISM wants; the island's loop stays one (flag 1).
// The fort.14's open segments are the same (every edge of the loop in one of them), and
// so are the other formats' that number open segments: two .pli files, two Gmsh groups,
// two MIKE codes, two nodestrings.
TEST(MeshOutputs, Gr3WritesAWholeLoopOfTheExteriorAsTwoSegments) {
  const Fixture f;
  TempDir dir;
  for (const bool open : {true, false}) {
    MeshOutputData d = f.data();
    const std::vector<Point2> round{{kX0 - 10, kY0 - 10},
                                    {kX0 + 3010, kY0 - 10},
                                    {kX0 + 3010, kY0 + 3010},
                                    {kX0 - 10, kY0 + 3010},
                                    {kX0 - 10, kY0 - 10}};
    d.boundary = extract_boundary(f.mesh, open ? PolylineIndex({round}) : PolylineIndex(), 20.0);
    const std::string gr3 = dir.file(open ? "open.gr3" : "lake.gr3");
    const std::string fort14 = dir.file(open ? "open.14" : "lake.14");
    write_mesh_outputs(d, {{gr3, "", false}, {fort14, "", false}});
    const Gr3 g = parse_gr3(read_file(gr3));
    EXPECT_EQ(parse_gr3(read_file(fort14)).open, g.open);
    ASSERT_EQ(g.open.size(), open ? 2u : 0u);
    ASSERT_EQ(g.land.size(), open ? 1u : 3u);
    EXPECT_EQ(g.land.back().first, 1);  // the island
    EXPECT_EQ(g.land.back().second.size(), 4u);
    const auto& halves =
        open ? g.open : std::vector<std::vector<int>>{g.land[0].second, g.land[1].second};
    if (!open) {
      EXPECT_EQ(g.land[0].first, 0);
      EXPECT_EQ(g.land[1].first, 0);
    }
    ASSERT_EQ(halves.size(), 2u);
    EXPECT_EQ(halves[0].back(), halves[1].front());
    EXPECT_EQ(halves[1].back(), halves[0].front());
    EXPECT_EQ(halves[0].size() + halves[1].size(), 12u + 2u);  // the 12 nodes round, 2 shared
    expect_segments_cover_the_boundary(g);
    if (!open) continue;
    MeshWriteOptions groups;
    groups.msh_groups = "segment";
    write_mesh_outputs(d,
                       {{dir.file("open.pli"), "", false},
                        {dir.file("open.msh"), "", false},
                        {dir.file("open.mesh"), "", false},
                        {dir.file("open.2dm"), "", false}},
                       groups);
    for (int k = 1; k <= 2; ++k) {
      std::istringstream pli(read_file(dir.file("open_" + std::to_string(k) + ".pli")));
      std::string name;
      std::size_t rows = 0;
      pli >> name >> rows;
      EXPECT_EQ(rows, g.open[k - 1].size()) << k;
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("open.pli")));
    const std::string msh = read_file(dir.file("open.msh"));
    EXPECT_NE(msh.find("\"open_1\""), std::string::npos);
    EXPECT_NE(msh.find("\"open_2\""), std::string::npos);
    std::set<int> codes;
    std::istringstream mesh(read_file(dir.file("open.mesh")));
    std::string line;
    std::getline(mesh, line);
    for (int i = 0; i < 16 && std::getline(mesh, line); ++i) {
      std::istringstream node(line);
      double id, x, y, z;
      int code;
      node >> id >> x >> y >> z >> code;
      codes.insert(code);
    }
    EXPECT_EQ(codes, (std::set<int>{1, 2, 3}));  // the island, two open segments (none inside)
    // Read back by MIKE's rule (a face takes its end node's code), the codes give the two
    // segments again, each face of each in it: the shared nodes end the segment before.
    std::vector<std::vector<int>> read_back;
    for (const std::vector<int>& run : read_mesh(dir.file("open.mesh")).open_boundaries) {
      read_back.emplace_back();
      for (int n : run) read_back.back().push_back(n + 1);
    }
    std::vector<std::vector<int>> written = g.open;
    std::sort(read_back.begin(), read_back.end());
    std::sort(written.begin(), written.end());
    EXPECT_EQ(read_back, written);
    std::istringstream dm(read_file(dir.file("open.2dm")));
    std::size_t strings = 0;  // each ends with a negative id
    while (std::getline(dm, line)) {
      std::istringstream card(line);
      std::string name;
      card >> name;
      for (int id = 0; name == "NS" && card >> id;) strings += id < 0;
    }
    EXPECT_EQ(strings, 2u + 2u);  // the open halves, the island's two
  }
}

// --schism-split: the quad that fails SCHISM's checks (its south-west corner slid east:
// angles 51 and 129 degrees, sides 200 to 1280 m) is two counter-clockwise triangles in
// its place, across the diagonal of the smaller skewness sum (from the slid corner), in
// hgrid.gr3 and hgrid.ll alike; the others stay quads, the boundary as before.
TEST(MeshOutputs, Gr3SplitsTheQuadsThatFailSchismsChecks) {
  Fixture f;
  f.mesh.points[0].x += 800;
  ASSERT_TRUE(fails_schism_checks(f.mesh, 0));
  for (int q = 1; q < 8; ++q) ASSERT_FALSE(fails_schism_checks(f.mesh, q)) << q;
  TempDir dir;
  MeshWriteOptions split;
  split.schism_split = true;
  write_mesh_outputs(f.data(), {{dir.file("quads.gr3"), "", false}});
  write_mesh_outputs(f.data(), {{dir.file("split.gr3"), "", false}}, split);
  const Gr3 quads = parse_gr3(read_file(dir.file("quads.gr3")));
  const Gr3 g = parse_gr3(read_file(dir.file("split.gr3")));
  ASSERT_EQ(quads.elements.size(), 8u);
  ASSERT_EQ(g.elements.size(), 9u);
  const std::vector<int> t0{1, 2, 6}, t1{1, 6, 5};  // quad 0 is 1, 2, 6, 5
  EXPECT_EQ(g.elements[0], t0);
  EXPECT_EQ(g.elements[1], t1);
  double area = 0;
  for (int e = 0; e < 2; ++e) {
    const auto& t = g.elements[e];
    const auto& a = g.nodes[t[0] - 1];
    const auto& b = g.nodes[t[1] - 1];
    const auto& c = g.nodes[t[2] - 1];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    EXPECT_GT(twice, 0) << e;  // counter-clockwise
    area += 0.5 * twice;
  }
  EXPECT_NEAR(area, quad_area(f.mesh, 0), 1e-6);
  for (int q = 1; q < 8; ++q) EXPECT_EQ(g.elements[q + 1], quads.elements[q]) << q;
  EXPECT_EQ(g.nodes, quads.nodes);
  EXPECT_EQ(g.open, quads.open);
  EXPECT_EQ(g.land, quads.land);
  EXPECT_EQ(parse_gr3(read_file(dir.file("split.ll"))).elements, g.elements);
}

// A mesh file read by gmsh and written again as MSH 2.2 (gmsh numbers nodes its own way):
// the physical names by tag, the node count, and each element's type, physical tag and
// nodes.
struct GmshRewrite {
  std::map<int, std::string> names;
  std::size_t num_nodes = 0;
  struct Element {
    int type = 0, physical = 0;
    std::vector<int> nodes;
  };
  std::vector<Element> elements;
};

GmshRewrite rewrite_with_gmsh(const TempDir& dir, const std::string& path) {
  GmshRewrite g;
  const std::string out = path + ".re.msh";
  const CliResult r = run_cli_program("gmsh", {path, "-0", "-format", "msh22", "-o", out}, dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find("Error"), std::string::npos) << r.err;
  std::istringstream in(read_file(out));
  std::string line;
  while (std::getline(in, line)) {
    if (line == "$PhysicalNames") {
      int n = 0;
      in >> n;
      for (int i = 0; i < n; ++i) {
        int dim = 0, tag = 0;
        std::string name;
        in >> dim >> tag >> name;
        g.names[tag] = name;
      }
    } else if (line == "$Nodes") {
      in >> g.num_nodes;
    } else if (line == "$Elements") {
      int n = 0;
      in >> n;
      for (int i = 0; i < n; ++i) {
        int id = 0, ntags = 0, tag = 0;
        GmshRewrite::Element e;
        in >> id >> e.type >> ntags >> e.physical;
        for (int t = 1; t < ntags; ++t) in >> tag;
        std::getline(in, line);
        std::istringstream nodes(line);
        for (int v; nodes >> v;) e.nodes.push_back(v);
        g.elements.push_back(e);
      }
    }
  }
  return g;
}

TEST(MeshOutputs, GmshReadsBothVersionsWithPhysicalGroups) {
  const Fixture f;
  TempDir dir;
  MeshWriteOptions o22;
  o22.msh_version = "2.2";
  write_mesh_outputs(f.data(), {{dir.file("m41.msh"), "", false}});
  write_mesh_outputs(f.data(), {{dir.file("m22.msh"), "", false}}, o22);
  EXPECT_EQ(read_file(dir.file("m41.msh")).substr(0, 23), "$MeshFormat\n4.1 0 8\n$En");
  EXPECT_EQ(read_file(dir.file("m22.msh")).substr(0, 23), "$MeshFormat\n2.2 0 8\n$En");
  for (const std::string name : {"m41", "m22"}) {
    // gmsh reads the file and writes it again (2.2); we count what it kept.
    const GmshRewrite g = rewrite_with_gmsh(dir, dir.file(name + ".msh"));
    std::map<std::pair<int, int>, int> count;  // (element type, physical) -> count
    for (const auto& e : g.elements) ++count[{e.type, e.physical}];
    std::map<int, std::string> names = g.names;
    EXPECT_EQ(g.num_nodes, 16u) << name;
    EXPECT_EQ(names[1], "\"land\"");
    EXPECT_EQ(names[2], "\"open\"");
    EXPECT_EQ(names[3], "\"domain\"");
    EXPECT_EQ(count[std::make_pair(3, 3)], 8) << name;   // quads, domain
    EXPECT_EQ(count[std::make_pair(1, 1)], 13) << name;  // lines, land (9 + island 4)
    EXPECT_EQ(count[std::make_pair(1, 2)], 3) << name;   // lines, open
    EXPECT_EQ(count.size(), 3u) << name;
  }
}

// --msh-groups segment: each open segment its own physical group, in hgrid.gr3's order;
// gmsh reads them back.
TEST(MeshOutputs, GmshGroupsOpenSegmentsOneByOne) {
  const Fixture f;
  TempDir dir;
  MeshOutputData d = f.data();
  // Open along the bottom and the top sides: two open segments.
  const std::vector<Point2> bottom{{kX0 - 1000, kY0}, {kX0 + 4000, kY0}};
  const std::vector<Point2> top{{kX0 - 1000, kY0 + 3 * kStep}, {kX0 + 4000, kY0 + 3 * kStep}};
  d.boundary = extract_boundary(f.mesh, PolylineIndex({bottom, top}), 1.0);
  std::vector<const BoundarySegment*> open;
  for (const BoundarySegment& s : d.boundary.segments)
    if (s.kind == BoundaryKind::open) open.push_back(&s);
  ASSERT_EQ(open.size(), 2u);
  for (const std::string version : {"4.1", "2.2"}) {
    MeshWriteOptions o;
    o.msh_version = version;
    o.msh_groups = "segment";
    const std::string path = dir.file("m" + version + ".msh");
    write_mesh_outputs(d, {{path, "", false}}, o);
    const GmshRewrite g = rewrite_with_gmsh(dir, path);
    std::map<int, std::set<std::pair<int, int>>> edges;  // physical -> edges (gmsh's nodes)
    for (const auto& e : g.elements)
      if (e.type == 1 && e.nodes.size() == 2)
        edges[e.physical].insert(std::minmax(e.nodes[0], e.nodes[1]));
    EXPECT_EQ(g.names,
              (std::map<int, std::string>{
                  {1, "\"land\""}, {3, "\"domain\""}, {11, "\"open_1\""}, {12, "\"open_2\""}}))
        << version;
    // Each segment's edges (gmsh numbers the nodes its own way: the counts, and the
    // two groups apart).
    for (int k = 0; k < 2; ++k)
      EXPECT_EQ(edges[11 + k].size(), open[k]->nodes.size() - 1) << version << " open_" << k + 1;
    for (const auto& e : edges[11]) EXPECT_EQ(edges[12].count(e), 0u) << version;
    EXPECT_EQ(edges.count(2), 0u) << version;
  }
}

// fort.14 of the fixture against its golden file (rewritten with ISOQUAD_UPDATE_GOLDEN
// set, as hgrid.gr3's): its nodes are hgrid.ll's, in longitude and latitude.
TEST(MeshOutputs, Fort14MatchesGolden) {
  const Fixture f;
  TempDir dir;
  write_mesh_outputs(f.data(),
                     {{dir.file("fort.14"), "", false}, {dir.file("hgrid.gr3"), "", false}});
  const std::string text = read_file(dir.file("fort.14"));
  if (std::getenv("ISOQUAD_UPDATE_GOLDEN")) write_file(golden("fort.14"), text);
  EXPECT_EQ(text, read_file(golden("fort.14")));
  // The node lines are hgrid.ll's.
  std::istringstream a(text), b(read_file(dir.file("hgrid.ll")));
  std::string la, lb;
  for (int i = 0; i < 2; ++i) std::getline(a, la), std::getline(b, lb);
  for (std::size_t i = 0; i < f.mesh.points.size(); ++i) {
    std::getline(a, la);
    std::getline(b, lb);
    EXPECT_EQ(la, lb) << i;
  }
}

// fort.14 of a land domain with a hole: no open boundary; the outer loop one mainland
// segment (IBTYPE 20) and the hole an island (21), each closed by its first node again.
TEST(MeshOutputs, AdcircLandDomainHasClosedFluxBoundaries) {
  const Fixture f;
  TempDir dir;
  MeshOutputData d = f.data();
  d.boundary = extract_boundary(f.mesh, PolylineIndex(), 0.0);
  MeshWriteOptions o;
  o.output_crs = "EPSG:32631";  // the fixture's own metres (ICS = 1)
  write_mesh_outputs(d, {{dir.file("fort.14"), "", false}}, o);
  std::istringstream in(read_file(dir.file("fort.14")));
  std::string line;
  std::getline(in, line);
  std::size_t ne = 0, np = 0;
  in >> ne >> np;
  EXPECT_EQ(ne, 16u);
  EXPECT_EQ(np, 16u);
  std::getline(in, line);  // the rest of the counts' line
  for (std::size_t i = 0; i < np + ne; ++i) std::getline(in, line);
  std::size_t nope = 9, neta = 9, nbou = 0, nvel = 0;
  in >> nope;
  std::getline(in, line);
  in >> neta;
  std::getline(in, line);
  EXPECT_EQ(nope, 0u);
  EXPECT_EQ(neta, 0u);
  in >> nbou;
  std::getline(in, line);
  in >> nvel;
  std::getline(in, line);
  ASSERT_EQ(nbou, 2u);
  EXPECT_EQ(nvel, 13u + 5u);  // 12 outer nodes and 4 round the hole, each closed
  for (const auto& [count, type] : {std::pair<std::size_t, int>{13, 20}, {5, 21}}) {
    std::size_t n = 0;
    int ibtype = 0;
    in >> n >> ibtype;
    std::getline(in, line);
    EXPECT_EQ(n, count);
    EXPECT_EQ(ibtype, type);
    std::vector<int> nodes(n);
    for (int& v : nodes) in >> v;
    EXPECT_EQ(nodes.front(), nodes.back()) << type;
    EXPECT_EQ(std::set<int>(nodes.begin(), nodes.end()).size(), n - 1) << type;
  }
  EXPECT_FALSE(in.fail());
}

TEST(MeshOutputs, LegacyVtkLoadsInMeshio) {
  const Fixture f;
  TempDir dir;
  write_mesh_outputs(f.data(), {{dir.file("m.vtk"), "", false}});
  python_check(dir,
             "import sys, meshio, numpy as np\n"
             "m = meshio.read(sys.argv[1])\n"
             "assert list(m.cells_dict) == ['quad'], m.cells_dict.keys()\n"
             "assert m.cells_dict['quad'].shape == (8, 4)\n"
             "assert m.cells_dict['quad'][0].tolist() == [0, 1, 5, 4]\n"
             "assert m.points.shape[0] == 16 and m.points[5][0] == 501000\n"
             "assert np.allclose(np.ravel(m.cell_data['size_ratio'][0]), 1 + 0.01 * np.arange(8))\n"
             "assert np.allclose(np.ravel(m.point_data['depth']), 10 + 0.5 * np.arange(16))\n"
             "assert np.ravel(m.point_data['degree']).tolist()[5] == 3\n",
             {dir.file("m.vtk")});
}

TEST(MeshOutputs, VtuArraysOfEveryLengthLoadInMeshio) {
  // The arrays are base64 encoded as they are written: with their 8-byte counts, 5 points
  // (128 bytes), 7 corners (64), 2 offsets (24) and 2 types (10) leave 2, 1, 0 and 1
  // bytes after the last full group of three, each padded its own way.
  const std::vector<Point2> points = {{0, 0}, {2, 0}, {2, 1}, {0, 1}, {3, 0.5}};
  VtuMesh mesh;
  mesh.points = &points;
  mesh.cells = {{0, 1, 2, 3}, {1, 4, 2}};
  mesh.point_data = {{"depth", {1.5, -2.25, 3e10, 0.0, 7.0}}};
  mesh.cell_data = {{"size_ratio", {0.75, 1.125}}};
  TempDir dir;
  write_vtu(mesh, dir.file("m.vtu"), false);
  python_check(
      dir,
      "import sys, meshio, numpy as np\n"
      "m = meshio.read(sys.argv[1])\n"
      "assert m.cells_dict['quad'].tolist() == [[0, 1, 2, 3]], m.cells_dict\n"
      "assert m.cells_dict['triangle'].tolist() == [[1, 4, 2]], m.cells_dict\n"
      "assert m.points.tolist() == [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [3, 0.5, 0]]\n"
      "assert np.ravel(m.point_data['depth']).tolist() == [1.5, -2.25, 3e10, 0.0, 7.0]\n"
      "sr = [np.ravel(b).tolist() for b in m.cell_data['size_ratio']]\n"
      "assert sorted(sum(sr, [])) == [0.75, 1.125], sr\n",
      {dir.file("m.vtu")});
}

TEST(MeshOutputs, UgridNetcdfHasTheRequiredAttributes) {
  const Fixture f;
  TempDir dir;
  write_mesh_outputs(f.data(), {{dir.file("m.nc"), "", false}});
  python_check(
      dir,
      "import sys, netCDF4, numpy as np\n"
      "d = netCDF4.Dataset(sys.argv[1])\n"
      "assert 'UGRID-1.0' in d.Conventions\n"
      "m = d['mesh']\n"
      "assert m.cf_role == 'mesh_topology' and m.topology_dimension == 2\n"
      "x, y = (d[v] for v in m.node_coordinates.split())\n"
      "assert len(x) == 16 and x.units == 'm' and x.grid_mapping == 'projected_coordinate_system'\n"
      "fn = d[m.face_node_connectivity]\n"
      "assert fn.cf_role == 'face_node_connectivity' and fn.start_index == 1\n"
      "assert fn._FillValue == -1 and fn.shape == (8, 4)\n"
      "assert fn.dimensions[0] == m.face_dimension\n"
      "faces = fn[:]\n"
      "assert faces[0].tolist() == [1, 2, 6, 5] and faces[7].tolist() == [11, 12, 16, 15]\n"
      "en = d[m.edge_node_connectivity]\n"
      "assert en.cf_role == 'edge_node_connectivity' and en.shape == (24, 2) and en.start_index == "
      "1\n"
      "assert en.dimensions[0] == m.edge_dimension\n"
      "edges = {tuple(sorted(e)) for e in en[:].tolist()}\n"
      "want = {tuple(sorted((f[i], f[(i + 1) % 4]))) for f in faces.tolist() for i in range(4)}\n"
      "assert edges == want, (edges ^ want)\n"
      "c = d['projected_coordinate_system']\n"
      "assert 'UTM zone 31N' in c.crs_wkt\n"
      "assert c.grid_mapping_name == 'transverse_mercator', c.grid_mapping_name\n"
      "assert c.longitude_of_central_meridian == 3 and c.scale_factor_at_central_meridian == "
      "0.9996\n"
      "assert c.false_easting == 500000 and c.semi_major_axis == 6378137\n"
      "assert c[:] == 32631 and c.epsg == 32631, (c[:], c.epsg)\n"
      "dep = d['depth']\n"
      "assert dep.location == 'node' and dep.mesh == 'mesh' and dep.positive == 'down'\n"
      "assert dep.long_name == 'depth (positive down)'\n"
      "assert np.allclose(dep[:], 10 + 0.5 * np.arange(16))\n"
      "z = d['mesh_node_z']\n"
      "assert z.standard_name == 'altitude' and z.location == 'node' and z.mesh == 'mesh'\n"
      "assert np.allclose(z[:], -dep[:])\n"
      "assert d['size_ratio'].location == 'face' and len(d['size_ratio']) == 8\n",
      {dir.file("m.nc")});
}

// TELEMAC's .cli: the mesh turned by 180 degrees, so that its first vertex is the
// north-east corner: the lines still start at the south-west corner and run
// counter-clockwise round the outer contour, then clockwise round the island from its
// south-west node; the bottom side (on the open ring) has the open boundary's codes.
TEST(MeshOutputs, TelemacBoundaryRunsFromTheSouthWestNode) {
  Fixture f;
  for (Point2& p : f.mesh.points) p = {2 * kX0 + 3 * kStep - p.x, 2 * kY0 + 3 * kStep - p.y};
  TempDir dir;
  write_mesh_outputs(f.data(), {{dir.file("m.slf"), "", false}});
  std::istringstream in(read_file(dir.file("m.cli")));
  std::vector<int> nodes;
  std::vector<std::string> codes;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string a, b, c, n, k;
    fields >> a >> b >> c;
    for (int i = 0; i < 9; ++i) fields >> n;
    fields >> k;
    codes.push_back(a + b + c);
    nodes.push_back(std::stoi(n));
    EXPECT_EQ(std::stoul(k), nodes.size());
  }
  EXPECT_EQ(nodes, (std::vector<int>{16, 15, 14, 13, 9, 5, 1, 2, 3, 4, 8, 12, 11, 7, 6, 10}));
  for (std::size_t k = 0; k < codes.size(); ++k) EXPECT_EQ(codes[k], k < 4 ? "544" : "222") << k;
}

// MIKE 21/3 FM .mesh: every node with its bed level and code, the quads counter-clockwise;
// boundary faces coded as DHI's mesh library codes them (land where either node is land,
// else the end node's code) give the open segment's edges code 2 and the rest 1.
TEST(MeshOutputs, MikeMeshCodesMakeTheOpenSegmentsFacesOpen) {
  const Fixture f;
  TempDir dir;
  const MeshOutputData d = f.data();
  write_mesh_outputs(d, {{dir.file("bay.mesh"), "", false}});
  std::istringstream in(read_file(dir.file("bay.mesh")));
  std::string item, unit, projection;
  std::size_t np = 0;
  in >> item >> unit >> np >> std::ws;
  std::getline(in, projection);
  EXPECT_EQ(item, "100079");  // bathymetry
  EXPECT_EQ(unit, "1000");    // metres
  ASSERT_EQ(np, f.mesh.points.size());
  EXPECT_EQ(projection.rfind("PROJCS[\"WGS_1984_UTM_Zone_31N\"", 0), 0u) << projection;
  std::vector<Point2> xy(np);
  std::vector<int> code(np);
  for (std::size_t i = 0; i < np; ++i) {
    std::size_t id = 0;
    double z = 0;
    in >> id >> xy[i].x >> xy[i].y >> z >> code[i];
    EXPECT_EQ(id, i + 1);
    EXPECT_NEAR(xy[i].x, f.mesh.points[i].x, 1e-6);
    EXPECT_NEAR(xy[i].y, f.mesh.points[i].y, 1e-6);
    EXPECT_DOUBLE_EQ(z, -(10.0 + 0.5 * i));  // the bed level
    EXPECT_GT(code[i], 0) << "boundary node " << i + 1 << " without a code";
  }
  std::size_t ne = 0, max_nodes = 0, kind = 0;
  in >> ne >> max_nodes >> kind;
  EXPECT_EQ(max_nodes, 4u);
  EXPECT_EQ(kind, 25u);  // quadrilaterals present
  ASSERT_EQ(ne, f.mesh.quads.size());
  std::map<std::pair<int, int>, int> faces;  // directed, counter-clockwise round each quad
  for (std::size_t e = 0; e < ne; ++e) {
    std::size_t id = 0;
    std::array<int, 4> n{};
    in >> id >> n[0] >> n[1] >> n[2] >> n[3];
    EXPECT_EQ(id, e + 1);
    double area2 = 0;
    for (int k = 0; k < 4; ++k) {
      const Point2 a = xy[n[k] - 1], b = xy[n[(k + 1) % 4] - 1];
      area2 += a.x * b.y - b.x * a.y;
      ++faces[{n[k], n[(k + 1) % 4]}];
    }
    EXPECT_GT(area2, 0) << "element " << id << " not counter-clockwise";
  }
  EXPECT_FALSE(in.fail());
  int open_faces = 0;
  for (const auto& [face, count] : faces) {
    if (faces.count({face.second, face.first})) continue;  // shared: inside
    const int from = code[face.first - 1], to = code[face.second - 1];
    const int face_code = from == 1 || to == 1 ? 1 : to;
    const bool south = xy[face.first - 1].y == kY0 && xy[face.second - 1].y == kY0;
    EXPECT_EQ(face_code, south ? 2 : 1) << face.first << "-" << face.second;
    open_faces += face_code == 2;
  }
  EXPECT_EQ(open_faces, 3);
  // Longitudes and latitudes on WGS 84 are MIKE's LONG/LAT.
  MeshWriteOptions o;
  o.output_crs = "EPSG:4326";
  write_mesh_outputs(d, {{dir.file("ll.mesh"), "", false}}, o);
  std::istringstream ll(read_file(dir.file("ll.mesh")));
  std::getline(ll, projection);
  EXPECT_EQ(projection, "100079 1000 16 LONG/LAT");
}

TEST(MeshOutputs, FormatByExtensionOrName) {
  EXPECT_EQ(mesh_output_format({"a.GPKG", "", false}), MeshFormat::gpkg);
  EXPECT_EQ(mesh_output_format({"a.msh", "", false}), MeshFormat::msh);
  EXPECT_EQ(mesh_output_format({"a.dat", "gr3", false}), MeshFormat::gr3);
  EXPECT_EQ(mesh_output_format({"a.2DM", "", false}), MeshFormat::sms2dm);
  EXPECT_EQ(mesh_output_format({"bay.mesh", "", false}), MeshFormat::mike);
  EXPECT_EQ(mesh_output_format({"bay.txt", "mesh", false}), MeshFormat::mike);
  EXPECT_EQ(mesh_output_files({"d/geo.slf", "", false}),
            (std::vector<std::string>{"d/geo.slf", "d/geo.cli"}));
  EXPECT_EQ(mesh_output_files({"d/hgrid.gr3", "", false}),
            (std::vector<std::string>{"d/hgrid.gr3", "d/hgrid.ll"}));
  EXPECT_EQ(mesh_output_format({"out/fort.14", "", false}), MeshFormat::fort14);
  EXPECT_EQ(mesh_output_format({"a.grd", "14", false}), MeshFormat::fort14);
  EXPECT_THROW(mesh_output_format({"a.dat", "", false}), Error);
  EXPECT_THROW(mesh_output_format({"a.gpkg", "shp", false}), Error);
}

// Longitudes across the antimeridian move into [0, 360) so that no quad spans the globe;
// a mesh that does not cross it, or that goes round a pole, keeps its longitudes.
TEST(MeshOutputs, LongitudesAcrossTheAntimeridianAreUnwrapped) {
  QuadMesh m;  // two quads side by side, 1 degree wide, the middle column at 180
  m.points = {{179, 0}, {180, 0}, {-179, 0}, {179, 1}, {180, 1}, {-179, 1}};
  m.quads = {{0, 1, 4, 3}, {1, 2, 5, 4}};
  std::vector<Point2> ll = m.points;
  EXPECT_TRUE(unwrap_antimeridian(m, ll));
  EXPECT_DOUBLE_EQ(ll[2].x, 181.0);
  EXPECT_DOUBLE_EQ(ll[5].x, 181.0);
  EXPECT_DOUBLE_EQ(ll[0].x, 179.0);
  EXPECT_DOUBLE_EQ(ll[2].y, 0.0);
  // West of it: unchanged.
  std::vector<Point2> west = {{10, 0}, {11, 0}, {12, 0}, {10, 1}, {11, 1}, {12, 1}};
  const std::vector<Point2> before = west;
  EXPECT_FALSE(unwrap_antimeridian(m, west));
  EXPECT_EQ(west.size(), before.size());
  for (std::size_t i = 0; i < west.size(); ++i) EXPECT_EQ(west[i].x, before[i].x);
  // A ring of quads round the pole spans every longitude whatever the cut: unchanged.
  QuadMesh ring;
  for (int k = 0; k < 4; ++k) {
    const double lon = -180 + 90 * k;
    ring.points.push_back({lon, 80});
    ring.points.push_back({lon, 85});
  }
  for (int k = 0; k < 4; ++k) {
    const int a = 2 * k, b = 2 * ((k + 1) % 4);
    ring.quads.push_back({a, b, b + 1, a + 1});
  }
  std::vector<Point2> polar = ring.points;
  EXPECT_FALSE(unwrap_antimeridian(ring, polar));
  EXPECT_DOUBLE_EQ(polar[0].x, -180.0);
}

// A failure while writing the second output (its temporary file cannot be created)
// leaves neither output, nor any temporary file.
TEST(MeshOutputs, FailureMidWriteLeavesNothing) {
  const Fixture f;
  TempDir dir;
  const std::string blocker = dir.file(".b.tmp-" + std::to_string(getpid()) + ".vtk");
  std::filesystem::create_directory(blocker);
  write_file(blocker + "/keep", "x");
  try {
    write_mesh_outputs(f.data(), {{dir.file("a.gpkg"), "", false}, {dir.file("b.vtk"), "", false}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::output) << e.what();
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{".b.tmp-" + std::to_string(getpid()) + ".vtk"});
  // Once the obstacle is gone the same call writes both.
  std::filesystem::remove_all(blocker);
  write_mesh_outputs(f.data(), {{dir.file("a.gpkg"), "", false}, {dir.file("b.vtk"), "", false}});
  EXPECT_EQ(dir.entries().size(), 2u);
}

// read_mesh reads back what the writers write: the same nodes (to the files' precision)
// and the same quads in every format that holds quads; ADCIRC's .14 two triangles per
// quad over the same area; the MIKE file's projection and the UGRID file's grid mapping
// as their CRS.
TEST(MeshOutputs, ReadMeshReadsBackEveryFormat) {
  const Fixture f;
  TempDir dir;
  double area = 0;
  for (int q = 0; q < static_cast<int>(f.mesh.quads.size()); ++q) area += quad_area(f.mesh, q);
  for (const std::string version : {"4.1", "2.2"}) {
    MeshWriteOptions options;
    options.msh_version = version;
    const std::string stem = "m" + std::string(version == "2.2" ? "22" : "41");
    std::vector<MeshOutput> outputs;
    for (const char* ext : {".gr3", ".2dm", ".msh", ".mesh", ".nc"})
      outputs.push_back({dir.file(stem + ext), "", false});
    write_mesh_outputs(f.data(), outputs, options);
    for (const MeshOutput& o : outputs) {
      SCOPED_TRACE(o.path);
      const ReadMesh m = read_mesh(o.path);
      ASSERT_EQ(m.points.size(), f.mesh.points.size());
      for (std::size_t i = 0; i < m.points.size(); ++i)
        EXPECT_LT(distance(m.points[i], f.mesh.points[i]), 1e-5);
      EXPECT_EQ(m.quads, f.mesh.quads);
      EXPECT_TRUE(m.triangles.empty());
      // The .msh's boundary lines (its physical groups) are not elements of the mesh.
      const bool msh = o.path.find(".msh") != std::string::npos;
      EXPECT_EQ(m.num_skipped_elements > 0, msh);
      if (o.path.find(".mesh") != std::string::npos || o.path.find(".nc") != std::string::npos) {
        ASSERT_FALSE(m.crs.empty());
        EXPECT_EQ(parse_crs(m.crs, "the file's").name, parse_crs(f.crs_wkt, "EPSG:32631").name);
      }
      // The open boundaries: the .gr3's segments, the .mesh's runs of open faces, the
      // .msh's runs along its group "open".
      if (o.path.find(".gr3") != std::string::npos || o.path.find(".mesh") != std::string::npos ||
          msh) {
        std::vector<std::vector<int>> open;
        for (const BoundarySegment& segment : f.data().boundary.segments)
          if (segment.kind == BoundaryKind::open) open.push_back(segment.nodes);
        ASSERT_FALSE(open.empty());
        EXPECT_EQ(m.open_boundaries, open);
      } else {
        EXPECT_TRUE(m.open_boundaries.empty());
      }
      // The depths (a .gr3's) or bed levels (the others'), 10 + i / 2 m deep; none in a .msh.
      if (msh) {
        EXPECT_TRUE(m.node_values.empty());
      } else {
        const double sign = o.path.find(".gr3") != std::string::npos ? 1.0 : -1.0;
        ASSERT_EQ(m.node_values.size(), f.mesh.points.size());
        for (std::size_t i = 0; i < m.node_values.size(); ++i)
          EXPECT_NEAR(sign * m.node_values[i], 10.0 + 0.5 * i, 1e-5) << i;
      }
    }
  }
  // ADCIRC's grid in the mesh's CRS (ICS 1) and TELEMAC's Selafin: two triangles a quad.
  MeshWriteOptions utm;
  utm.output_crs = "EPSG:32631";
  write_mesh_outputs(f.data(), {{dir.file("fort.14"), "", false}, {dir.file("m.slf"), "", false}},
                     utm);
  for (const char* name : {"fort.14", "m.slf"}) {
    SCOPED_TRACE(name);
    const ReadMesh split = read_mesh(dir.file(name));
    EXPECT_EQ(split.format, std::string(name) == "m.slf" ? "slf" : "14");
    EXPECT_TRUE(split.notes.empty());  // the .14's land section read (none of it flux)
    EXPECT_EQ(split.num_flux_boundaries, 0u);
    EXPECT_TRUE(split.quads.empty());
    ASSERT_EQ(split.points.size(), f.mesh.points.size());
    for (std::size_t i = 0; i < split.points.size(); ++i)
      EXPECT_LT(distance(split.points[i], f.mesh.points[i]), 1e-5);
    ASSERT_EQ(split.triangles.size(), 2 * f.mesh.quads.size());
    double triangles = 0;
    for (const auto& t : split.triangles)
      triangles += signed_area(split.points[t[0]], split.points[t[1]], split.points[t[2]]);
    EXPECT_NEAR(triangles, area, 1e-3);
    // The open boundaries: fort.14's segments; the Selafin's from the .cli beside it.
    std::vector<std::vector<int>> open;
    for (const BoundarySegment& segment : f.data().boundary.segments)
      if (segment.kind == BoundaryKind::open) open.push_back(segment.nodes);
    EXPECT_EQ(split.open_boundaries, open);
    // fort.14's depths, the Selafin's BOTTOM (the bed level).
    const double sign = std::string(name) == "m.slf" ? -1.0 : 1.0;
    ASSERT_EQ(split.node_values.size(), f.mesh.points.size());
    for (std::size_t i = 0; i < split.node_values.size(); ++i)
      EXPECT_NEAR(sign * split.node_values[i], 10.0 + 0.5 * i, 1e-5) << i;
  }
  // A .cli naming a node the geometry lacks stops the reading at its line; without its
  // .cli, a Selafin has no open boundaries.
  write_file(dir.file("m.cli"), "5 4 4 0 0 0 0 4 0 0 0 1 1\n5 4 4 0 0 0 0 4 0 0 0 999 2\n");
  try {
    read_mesh(dir.file("m.slf"));
    ADD_FAILURE() << "node 999 read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("m.cli' line 2: node 999 is not among the geometry's"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove(dir.file("m.cli"));
  EXPECT_TRUE(read_mesh(dir.file("m.slf")).open_boundaries.empty());
}
