#include "mesh/background_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

#include "core/error.h"
#include "mesh/locate.h"
#include "unit/mesh/test_domains.h"

#include "app/front_end.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

BackgroundMeshParams uniform(double max_edge_m) {
  BackgroundMeshParams p;
  p.max_edge_m = [max_edge_m](const Point2&) { return max_edge_m; };
  return p;
}

double smallest_angle_deg(const BackgroundMesh& m, int f) {
  const auto& t = m.triangles[f];
  double smallest = 180.0;
  for (int i = 0; i < 3; ++i) {
    const Point2 &o = m.points[t[i]], &a = m.points[t[(i + 1) % 3]], &b = m.points[t[(i + 2) % 3]];
    const double ux = a.x - o.x, uy = a.y - o.y, vx = b.x - o.x, vy = b.y - o.y;
    smallest = std::min(smallest, std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / kPi);
  }
  return smallest;
}

double longest_edge_m(const BackgroundMesh& m, int f) {
  const auto& t = m.triangles[f];
  return std::max({distance(m.points[t[0]], m.points[t[1]]), distance(m.points[t[1]], m.points[t[2]]),
                   distance(m.points[t[2]], m.points[t[0]])});
}

std::vector<const Ring*> rings_of(const Domain& d) {
  std::vector<const Ring*> rings;
  for (const Polygon& p : d.polygons) {
    rings.push_back(&p.outer);
    for (const Ring& h : p.holes) rings.push_back(&h);
  }
  return rings;
}

// Every property the later stages rely on. min_angle_deg < 0 skips the angle check
// (real coastlines have small input angles, where no refinement can help).
void expect_valid_mesh(const Domain& d, const BackgroundMeshParams& params,
                       const BackgroundMesh& m, double min_angle_deg) {
  const int num_triangles = static_cast<int>(m.triangles.size());
  ASSERT_GT(num_triangles, 0);
  ASSERT_EQ(m.neighbours.size(), m.triangles.size());
  ASSERT_EQ(m.boundary_chain_of_vertex.size(), m.points.size());

  // Triangles: inside the domain, CCW, well shaped, small enough; total area.
  double area_m2 = 0.0;
  int num_outside = 0, num_small_angle = 0, num_too_long = 0;
  for (int f = 0; f < num_triangles; ++f) {
    const auto& t = m.triangles[f];
    const Point2 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    ASSERT_GT(twice, 0.0) << "triangle " << f << " is not counter-clockwise";
    area_m2 += 0.5 * twice;
    const Point2 g = centroid(m, f);
    if (!inside_domain(d, g)) ++num_outside;
    if (min_angle_deg >= 0 && smallest_angle_deg(m, f) < min_angle_deg) ++num_small_angle;
    if (longest_edge_m(m, f) > params.max_edge_m(g) * (1.0 + 1e-9)) ++num_too_long;
  }
  EXPECT_EQ(num_outside, 0);
  EXPECT_EQ(num_small_angle, 0);
  EXPECT_EQ(num_too_long, 0);
  EXPECT_NEAR(area_m2, area(d), 1e-9 * area(d));

  // Neighbours symmetric; collect directed boundary edges.
  std::set<std::pair<int, int>> boundary_edges;
  for (int f = 0; f < num_triangles; ++f)
    for (int i = 0; i < 3; ++i) {
      const int u = m.triangles[f][(i + 1) % 3], w = m.triangles[f][(i + 2) % 3];
      const int g = m.neighbours[f][i];
      if (g < 0) {
        EXPECT_TRUE(boundary_edges.insert({u, w}).second);
        continue;
      }
      ASSERT_LT(g, num_triangles);
      int back = 0;
      for (int j = 0; j < 3; ++j)
        if (m.neighbours[g][j] == f && m.triangles[g][(j + 1) % 3] == w &&
            m.triangles[g][(j + 2) % 3] == u)
          ++back;
      EXPECT_EQ(back, 1) << "triangles " << f << " and " << g;
    }

  // Chains: one per ring, on the ring, every input vertex in order, and their edges are
  // exactly the boundary edges (domain on the left).
  const std::vector<const Ring*> rings = rings_of(d);
  ASSERT_EQ(m.chains.size(), rings.size());
  std::set<std::pair<int, int>> chain_edges;
  std::size_t ring_index = 0;
  for (std::size_t p = 0; p < d.polygons.size(); ++p)
    for (std::size_t r = 0; r <= d.polygons[p].holes.size(); ++r, ++ring_index) {
      const BoundaryChain& chain = m.chains[ring_index];
      const Ring& ring = *rings[ring_index];
      EXPECT_EQ(chain.polygon, static_cast<int>(p));
      EXPECT_EQ(chain.ring, static_cast<int>(r));
      const std::size_t n = chain.vertices.size();
      ASSERT_GE(n, ring.size());
      ASSERT_EQ(chain.arc_length_m.size(), n);
      ASSERT_EQ(chain.is_corner.size(), n);
      ASSERT_EQ(chain.turning_angle_deg.size(), n);
      EXPECT_EQ(chain.arc_length_m[0], 0.0);
      EXPECT_NEAR(chain.length_m, perimeter(ring), 1e-9 * perimeter(ring));
      std::size_t next_input = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const int v = chain.vertices[k];
        EXPECT_EQ(m.boundary_chain_of_vertex[v], static_cast<int>(ring_index));
        const Point2& q = m.points[v];
        if (next_input < ring.size() && q == ring[next_input]) {
          EXPECT_TRUE(chain.is_input_vertex[k]);
          ++next_input;
        } else {
          EXPECT_FALSE(chain.is_input_vertex[k]);
          EXPECT_EQ(chain.turning_angle_deg[k], 0.0);
          // A Steiner point lies on the input segment it splits.
          ASSERT_GT(next_input, 0u);
          const Point2& a = ring[next_input - 1];
          const Point2& b = ring[next_input % ring.size()];
          EXPECT_LT(distance_to_segment(q, a, b), 1e-9 * distance(a, b));
        }
        if (k > 0) {
          EXPECT_GT(chain.arc_length_m[k], chain.arc_length_m[k - 1]);
        }
        chain_edges.insert({v, chain.vertices[(k + 1) % n]});
      }
      EXPECT_EQ(next_input, ring.size()) << "input vertices missing or out of order";
    }
  EXPECT_EQ(chain_edges, boundary_edges);
  const long num_boundary_vertices =
      std::count_if(m.boundary_chain_of_vertex.begin(), m.boundary_chain_of_vertex.end(),
                    [](int c) { return c >= 0; });
  EXPECT_EQ(static_cast<std::size_t>(num_boundary_vertices), chain_edges.size());
}

void expect_identical(const BackgroundMesh& a, const BackgroundMesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.neighbours, b.neighbours);
  EXPECT_EQ(a.boundary_chain_of_vertex, b.boundary_chain_of_vertex);
  ASSERT_EQ(a.chains.size(), b.chains.size());
  for (std::size_t c = 0; c < a.chains.size(); ++c) {
    EXPECT_EQ(a.chains[c].vertices, b.chains[c].vertices);
    EXPECT_EQ(a.chains[c].arc_length_m, b.chains[c].arc_length_m);
  }
}

}  // namespace

TEST(BackgroundMesh, SquareIsValidWellShapedAndSized) {
  const Domain d = square_domain(1000.0);
  const BackgroundMeshParams params = uniform(50.0);
  const BackgroundMesh m = build_background_mesh(d, params);
  expect_valid_mesh(d, params, m, 20.0);
  // Area / (area of an equilateral triangle of side 50 m) is a lower bound.
  EXPECT_GT(m.triangles.size(), 1e6 / (std::sqrt(3.0) / 4 * 50 * 50));
  // Four convex corners of +90 degrees.
  const BoundaryChain& chain = m.chains[0];
  int num_corners = 0;
  for (std::size_t k = 0; k < chain.vertices.size(); ++k)
    if (chain.is_corner[k]) {
      ++num_corners;
      EXPECT_NEAR(chain.turning_angle_deg[k], 90.0, 1e-9);
    }
  EXPECT_EQ(num_corners, 4);
  EXPECT_EQ(m.points[chain.vertices[0]], d.polygons[0].outer[0]);  // the chain starts there
}

TEST(BackgroundMesh, AnnulusKeepsTheHoleEmpty) {
  const Domain d = annulus_domain(1000.0, 300.0, 64);
  const BackgroundMeshParams params = uniform(40.0);
  const BackgroundMesh m = build_background_mesh(d, params);
  expect_valid_mesh(d, params, m, 20.0);
  // Walking the clockwise hole ring (domain on the left) turns right at every vertex:
  // seen from the domain, the hole's vertices are reflex.
  for (std::size_t k = 0; k < m.chains[1].vertices.size(); ++k)
    if (m.chains[1].is_input_vertex[k]) {
      EXPECT_NEAR(m.chains[1].turning_angle_deg[k], -360.0 / 64, 1e-9);
    }
  for (std::size_t k = 0; k < m.chains[0].vertices.size(); ++k)
    if (m.chains[0].is_input_vertex[k]) {
      EXPECT_NEAR(m.chains[0].turning_angle_deg[k], 360.0 / 64, 1e-9);
    }
}

TEST(BackgroundMesh, LShapeMarksTheReflexCorner) {
  const Domain d = l_domain(500.0);
  const BackgroundMeshParams params = uniform(30.0);
  const BackgroundMesh m = build_background_mesh(d, params);
  expect_valid_mesh(d, params, m, 20.0);
  int num_reflex = 0, num_convex = 0;
  const BoundaryChain& chain = m.chains[0];
  for (std::size_t k = 0; k < chain.vertices.size(); ++k) {
    if (!chain.is_corner[k]) continue;
    if (chain.turning_angle_deg[k] < 0) {
      ++num_reflex;
      EXPECT_NEAR(chain.turning_angle_deg[k], -90.0, 1e-9);
      EXPECT_EQ(m.points[chain.vertices[k]], (Point2{500.0, 500.0}));
    } else {
      ++num_convex;
    }
  }
  EXPECT_EQ(num_reflex, 1);
  EXPECT_EQ(num_convex, 5);
}

TEST(BackgroundMesh, TwoPolygonsOneWithAnIslandInsideItsHole) {
  Domain d = annulus_domain(1000.0, 500.0, 48);
  Polygon island{circle_ring(200.0, 24), {}};  // inside the hole: nesting level 3
  Polygon other;
  for (const Point2& q : circle_ring(300.0, 32)) other.outer.push_back({q.x + 2000.0, q.y});
  d.polygons.push_back(island);
  d.polygons.push_back(other);
  const BackgroundMeshParams params = uniform(60.0);
  const BackgroundMesh m = build_background_mesh(d, params);
  expect_valid_mesh(d, params, m, 20.0);
}

TEST(BackgroundMesh, VariableSizeGivesSmallerTrianglesWhereAsked) {
  const Domain d = square_domain(1000.0);
  BackgroundMeshParams params;
  params.max_edge_m = [](const Point2& p) { return 5.0 + 0.1 * p.x; };  // 5 m .. 105 m
  const BackgroundMesh m = build_background_mesh(d, params);
  expect_valid_mesh(d, params, m, 20.0);
  double left_sum = 0, right_sum = 0;
  int left_n = 0, right_n = 0;
  for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
    const Point2 g = centroid(m, f);
    if (g.x < 200) left_sum += longest_edge_m(m, f), ++left_n;
    if (g.x > 800) right_sum += longest_edge_m(m, f), ++right_n;
  }
  ASSERT_GT(left_n, 0);
  ASSERT_GT(right_n, 0);
  EXPECT_LT(left_sum / left_n * 3.0, right_sum / right_n);
  EXPECT_GT(left_n, 10 * right_n);
}

TEST(BackgroundMesh, IsDeterministic) {
  const Domain d = annulus_domain(1000.0, 300.0, 64);
  BackgroundMeshParams params;
  params.max_edge_m = [](const Point2& p) { return 20.0 + 0.05 * std::hypot(p.x, p.y); };
  const BackgroundMesh a = build_background_mesh(d, params);
  const BackgroundMesh b = build_background_mesh(d, params);
  expect_identical(a, b);
}

TEST(BackgroundMesh, RejectsCrossingRings) {
  Domain d = square_domain(1000.0);
  d.polygons[0].holes.push_back({{900, 500}, {900, 400}, {1100, 400}, {1100, 500}});  // CW, crosses
  try {
    build_background_mesh(d, uniform(100.0));
    FAIL() << "expected Error(input)";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input) << e.what();
  }
}

TEST(BackgroundMesh, RejectsWrongOrientationAndRepeatedVertices) {
  Domain d = square_domain(1000.0);
  std::reverse(d.polygons[0].outer.begin(), d.polygons[0].outer.end());
  EXPECT_THROW(build_background_mesh(d, uniform(100.0)), Error);
  Domain r = square_domain(1000.0);
  r.polygons[0].outer.insert(r.polygons[0].outer.begin() + 1, {1000, 0});
  EXPECT_THROW(build_background_mesh(r, uniform(100.0)), Error);
}

TEST(BackgroundMesh, RejectsAPolygonInsideAnother) {
  Domain d = square_domain(1000.0);
  d.polygons.push_back({{{400, 400}, {600, 400}, {600, 600}, {400, 600}}, {}});
  try {
    build_background_mesh(d, uniform(100.0));
    FAIL() << "expected Error(input)";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input) << e.what();
  }
}

TEST(BackgroundMesh, RejectsAHoleOutsideItsPolygon) {
  Domain d = square_domain(1000.0);
  d.polygons[0].holes.push_back({{2000, 0}, {2000, 100}, {2100, 100}, {2100, 0}});  // CW
  EXPECT_THROW(build_background_mesh(d, uniform(100.0)), Error);
}

TEST(BackgroundMesh, StopsARunawayRefinement) {
  BackgroundMeshParams params = uniform(1.0);
  params.max_num_vertices = 10000;  // about 1.2 million are needed
  try {
    build_background_mesh(square_domain(1000.0), params);
    FAIL() << "expected Error(meshing)";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::meshing) << e.what();
  }
}

TEST(BackgroundMesh, RejectsANonPositiveSize) {
  BackgroundMeshParams params;
  params.max_edge_m = [](const Point2& p) { return p.x < 500 ? 50.0 : 0.0; };
  EXPECT_THROW(build_background_mesh(square_domain(1000.0), params), Error);
}

TEST(BackgroundMesh, LargeSquareTiming) {
  const Domain d = square_domain(1000.0);
  const BackgroundMeshParams params = uniform(10.0);
  const auto start = std::chrono::steady_clock::now();
  const BackgroundMesh m = build_background_mesh(d, params);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("num_triangles", static_cast<int>(m.triangles.size()));
  std::printf("1000 m square, max edge 10 m: %zu vertices, %zu triangles, %.2f s\n",
              m.points.size(), m.triangles.size(), seconds);
  expect_valid_mesh(d, params, m, 20.0);
}

TEST(BackgroundMesh, RealSample) {
  FrontEndOptions options;
  options.read.path = std::string(ISOQUAD_SOURCE_DIR) + "/shapefiles/corsica.shp";
  options.target_size_m = 2000.0;
  const Domain d = build_planar_domain(options).domain;
  const BackgroundMeshParams params = uniform(400.0);  // 0.1 x tile size 2h
  const auto start = std::chrono::steady_clock::now();
  const BackgroundMesh m = build_background_mesh(d, params);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("corsica, max edge 400 m: %zu input vertices, %zu vertices, %zu triangles, %.2f s\n",
              num_vertices(d), m.points.size(), m.triangles.size(), seconds);
  expect_valid_mesh(d, params, m, -1.0);
  // Small angles only where the coastline itself has them.
  int num_small = 0;
  for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f)
    if (smallest_angle_deg(m, f) < 20.0) ++num_small;
  EXPECT_LT(num_small, static_cast<int>(m.triangles.size() / 100));
}

TEST(TriangleLocator, PointsOnEdgesAndVerticesAreInside) {
  // Lattice points of a square land exactly on vertices and edges of its mesh; rounding
  // in the barycentric coordinates must not put them outside every triangle.
  const BackgroundMesh m = build_background_mesh(square_domain(1000.0), uniform(25.0));
  const TriangleLocator locator(m);
  int outside = 0;
  for (const Point2& p : m.points) outside += !locator.locate(p).inside;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i) {
      const Point2 &a = m.points[t[i]], &b = m.points[t[(i + 1) % 3]];
      outside += !locator.locate({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}).inside;
    }
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) outside += !locator.locate({50.0 * i, 50.0 * j}).inside;
  EXPECT_EQ(outside, 0);
  // Outside the square: clamped to the nearest triangle, and said to be outside.
  const Location far = locator.locate({1000.5, 500.0});
  EXPECT_FALSE(far.inside);
  EXPECT_GE(far.triangle, 0);
}

TEST(TriangleLocator, PointsFarFromEveryTriangleGetWhatEveryRingGives) {
  // Two islands 100 km apart: most cells of the grid hold no triangle, and a point far
  // out skips the rings of cells round it that hold none. It must get the triangle,
  // coordinates and flag of the search through every ring.
  Domain d = square_domain(1000.0);
  Domain other = square_domain(1000.0);
  for (Point2& p : other.polygons[0].outer) p.x += 100000.0, p.y += 60000.0;
  d.polygons.push_back(other.polygons[0]);
  const BackgroundMesh m = build_background_mesh(d, uniform(25.0));
  const TriangleLocator locator(m);
  std::vector<Point2> points;
  for (int i = -4; i <= 24; ++i)
    for (int j = -4; j <= 16; ++j) points.push_back({5000.0 * i + 123.0, 5000.0 * j + 77.0});
  points.push_back({500.0, 500.0});
  points.push_back({100500.0, 60500.0});
  int far = 0;
  for (const Point2& p : points) {
    const Location fast = locator.locate(p);
    const Location every = locator.locate_visiting_every_ring(p);
    EXPECT_EQ(fast.triangle, every.triangle) << p.x << " " << p.y;
    EXPECT_EQ(fast.bary, every.bary) << p.x << " " << p.y;
    EXPECT_EQ(fast.inside, every.inside) << p.x << " " << p.y;
    far += !fast.inside && std::min(std::hypot(p.x - 500.0, p.y - 500.0),
                                    std::hypot(p.x - 100500.0, p.y - 60500.0)) > 20000.0;
  }
  EXPECT_GT(far, 400);
}

TEST(TriangleLocator, AHintGivesWhatTheSearchGives) {
  // Points inside, on edges and vertices, and outside, each with the triangle it is in,
  // a neighbour, a far triangle and no hint: the same triangle and coordinates.
  const BackgroundMesh m = build_background_mesh(square_domain(1000.0), uniform(25.0));
  const TriangleLocator locator(m);
  std::vector<Point2> points = {{1000.5, 500.0}, {-3.0, -3.0}};
  for (std::size_t f = 0; f < m.triangles.size(); f += 7) {
    const auto& t = m.triangles[f];
    const Point2 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    points.push_back({(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3});
    points.push_back({(a.x + b.x) / 2, (a.y + b.y) / 2});
    points.push_back(a);
  }
  int hits = 0;
  for (const Point2& p : points) {
    const Location plain = locator.locate(p);
    for (int hint : {plain.triangle, m.neighbours[std::max(plain.triangle, 0)][0], 0, -1}) {
      const Location hinted = locator.locate(p, hint);
      EXPECT_EQ(hinted.triangle, plain.triangle) << p.x << " " << p.y << " hint " << hint;
      EXPECT_EQ(hinted.bary, plain.bary);
      EXPECT_EQ(hinted.inside, plain.inside);
      hits += hint == plain.triangle;
    }
  }
  EXPECT_GT(hits, 100);
}
