// The only CGAL translation unit of the meshing stages: CGAL headers dominate compile
// time, and keeping CGAL types out of the header lets every later stage work on flat
// arrays.
//
// CGAL's checks stay on in Release builds (CGAL_DEBUG, set in CMakeLists.txt): its 2D
// mesher has known failures on some inputs (an assertion in Refine_edges.h when a vertex
// lies very close to a constrained edge, CGAL issue 781) that without them are a
// segmentation fault; with them, an exception this stage reports.
#include "mesh/background_mesh.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <string>
#include <utility>

#include "core/error.h"

namespace isoquad {

namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kStage = "mesh";
// The shares of build_background_mesh's time told to BackgroundMeshParams::progress when
// the seeds and the refinement are done (France at a uniform 3 km).
constexpr double kSeededShare = 0.55;
constexpr double kRefinedShare = 0.7;

struct FaceInfo {
  int nesting_level = -1;  // 0 outside, 1 in a polygon, 2 in its hole, ...
  int id = -1;             // output triangle id, -1 outside the domain
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // output vertex id
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
// Delaunay_mesh_face_base_2's default base, Constrained_Delaunay_triangulation_face_base_2,
// adds a face's blindness to its circumcentre (24 bytes a face), which only CGAL's
// constrained Voronoi diagram (Lloyd smoothing) reads: without it a face takes 72 bytes
// instead of 96, and the same triangulation is built (France at 1.5 km, 1.8 million
// vertices: the stage's peak 632 -> 550 MB).
using Cfb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K, Cfb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
// The "plus" wrapper keeps each ring as one constraint and follows the splits made by
// refinement, so the boundary chains can be read back in order.
using Ct = CGAL::Constrained_triangulation_plus_2<Cdt>;
using FaceHandle = Ct::Face_handle;
using VertexHandle = Ct::Vertex_handle;

using SizeOracle = std::function<double(const Point2&)>;

// Like CGAL::Delaunay_mesh_size_criteria_2, but the size bound is the oracle at the
// face centroid. The mesher copies the criteria and calls is_bad_object() on every
// evaluation, so both hold only a pointer to the caller's oracle and the bound.
class SizeAndAngleCriteria {
 public:
  // (squared sine of the smallest angle, (longest edge / max edge)^2); CGAL's ordering
  // refines size violations first, the largest first.
  using Quality = CGAL::Delaunay_mesh_size_criteria_2<Ct>::Quality;

  class Is_bad {
   public:
    Is_bad(const SizeOracle* max_edge_m, double squared_sine_bound)
        : max_edge_m_(max_edge_m), b_(squared_sine_bound) {}

    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const {
      if (q.size() > 1) return CGAL::Mesh_2::IMPERATIVELY_BAD;
      if (q.sine() < b_) return CGAL::Mesh_2::BAD;
      return CGAL::Mesh_2::NOT_BAD;
    }

    CGAL::Mesh_2::Face_badness operator()(const FaceHandle& fh, Quality& q) const {
      const K::Point_2& pa = fh->vertex(0)->point();
      const K::Point_2& pb = fh->vertex(1)->point();
      const K::Point_2& pc = fh->vertex(2)->point();
      const double a = CGAL::to_double(CGAL::squared_distance(pb, pc));
      const double b = CGAL::to_double(CGAL::squared_distance(pc, pa));
      const double c = CGAL::to_double(CGAL::squared_distance(pa, pb));
      const double max_sq = std::max({a, b, c});
      const double second_sq = std::max(std::min(a, b), std::min(std::max(a, b), c));

      const Point2 centroid{(pa.x() + pb.x() + pc.x()) / 3.0, (pa.y() + pb.y() + pc.y()) / 3.0};
      const double h = (*max_edge_m_)(centroid);
      if (!(h > 0.0))  // also catches NaN
        throw Error(ErrorClass::meshing, kStage,
                    "the sizing oracle returned " + std::to_string(h) + " m at (" +
                        std::to_string(centroid.x) + ", " + std::to_string(centroid.y) +
                        "); sizes must be positive");
      q.second = max_sq / (h * h);  // 0 when h is infinite: no size limit there
      if (q.size() > 1) {
        q.first = 1;  // the sine is irrelevant: size violations are refined regardless
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      const double twice_area = (pb.x() - pa.x()) * (pc.y() - pa.y()) -
                                (pb.y() - pa.y()) * (pc.x() - pa.x());
      q.first = twice_area * twice_area / (max_sq * second_sq);
      return q.sine() < b_ ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

   private:
    const SizeOracle* max_edge_m_;
    double b_;
  };

  SizeAndAngleCriteria(const SizeOracle* max_edge_m, double squared_sine_bound)
      : max_edge_m_(max_edge_m), b_(squared_sine_bound) {}

  Is_bad is_bad_object() const { return Is_bad(max_edge_m_, b_); }

 private:
  const SizeOracle* max_edge_m_;
  double b_;
};

// Floods faces from `start` with `level` without crossing constraints, collecting the
// constrained edges met on the way (the next level starts across them).
void flood_nesting_level(FaceHandle start, int level, std::vector<std::pair<FaceHandle, int>>& border) {
  if (start->info().nesting_level != -1) return;
  std::vector<FaceHandle> stack{start};
  start->info().nesting_level = level;
  while (!stack.empty()) {
    FaceHandle fh = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      FaceHandle n = fh->neighbor(i);
      if (n->info().nesting_level != -1) continue;
      if (fh->is_constrained(i)) {
        border.emplace_back(fh, i);
      } else {
        n->info().nesting_level = level;
        stack.push_back(n);
      }
    }
  }
}

// Marks the domain by nesting level (odd = inside): CGAL 5.5 has no
// mark_domain_in_triangulation, and the mesher's default marks the whole convex hull,
// holes included.
void mark_domain(Ct& ct) {
  for (auto f = ct.all_faces_begin(); f != ct.all_faces_end(); ++f) f->info().nesting_level = -1;
  std::vector<std::pair<FaceHandle, int>> border;
  flood_nesting_level(ct.infinite_face(), 0, border);
  // Breadth-first over levels so that each face gets the smallest crossing count.
  for (std::size_t k = 0; k < border.size(); ++k) {
    const auto [fh, i] = border[k];
    FaceHandle n = fh->neighbor(i);
    if (n->info().nesting_level == -1)
      flood_nesting_level(n, fh->info().nesting_level + 1, border);
  }
  for (auto f = ct.all_faces_begin(); f != ct.all_faces_end(); ++f)
    f->set_in_domain(f->info().nesting_level % 2 == 1);
}

// Seeds the inside of the domain with the centres of the leaves of a quadtree whose
// cells are as large as the size allows (side <= max_edge / 1.5, so the right-angled
// triangles between neighbouring centres meet the bound). Delaunay refinement from the
// boundary alone would insert every point one at a time through its queue of bad
// faces; after seeding it only mends the transitions and the boundary, several times
// faster. Seeds closer to the boundary than half a cell are left out: they would make
// refinement split the boundary edges very finely.
void seed_interior(Ct& ct, const Domain& domain, const BackgroundMeshParams& params) {
  const SizeOracle& size = params.max_edge_m;
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  std::vector<K::Point_2> boundary;
  for_each_side(domain, [&](const Point2& a, const Point2& b) {
    xmin = std::min(xmin, a.x), ymin = std::min(ymin, a.y);
    xmax = std::max(xmax, a.x), ymax = std::max(ymax, a.y);
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const double e = size({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)});
    const int n = std::max(1, static_cast<int>(std::ceil(len / (0.25 * e))));
    for (int k = 0; k < n; ++k)
      boundary.emplace_back(a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n);
  });
  using Traits = CGAL::Search_traits_2<K>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  Search::Tree tree(boundary.begin(), boundary.end());

  struct Cell {
    double x, y, side;
    int depth;
  };
  // Leaves are up to 8 times the local edge bound e, and small enough that e varies by
  // less than 25% over them; each is filled with a hexagonal lattice (rows d apart along
  // x, 0.87 d apart along y, every other row shifted by d / 2) whose edges are at most
  // 0.95 e: nearly equilateral triangles at close to the ideal density. Large leaves
  // keep the rounding of d small.
  // Component boxes: cells over none of them (the sea between islands far apart) are
  // neither split nor filled.
  std::vector<std::array<double, 4>> boxes;
  for (const Polygon& poly : domain.polygons) {
    std::array<double, 4> b{1e300, 1e300, -1e300, -1e300};
    for (const Point2& p : poly.outer)
      b = {std::min(b[0], p.x), std::min(b[1], p.y), std::max(b[2], p.x), std::max(b[3], p.y)};
    boxes.push_back(b);
  }
  auto overlaps_domain = [&boxes](double x0, double y0, double side) {
    for (const auto& b : boxes)
      if (x0 <= b[2] && b[0] <= x0 + side && y0 <= b[3] && b[1] <= y0 + side) return true;
    return false;
  };
  std::vector<Cell> stack{{xmin, ymin, std::max(xmax - xmin, ymax - ymin), 0}};
  std::vector<std::pair<K::Point_2, double>> leaves;  // (point, lattice spacing)
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    if (!overlaps_domain(c.x, c.y, c.side)) continue;
    const double e = size({c.x + 0.5 * c.side, c.y + 0.5 * c.side});
    if (!(e > 0.0))  // also catches NaN
      throw Error(ErrorClass::meshing, kStage,
                  "the sizing oracle returned " + std::to_string(e) + " m at (" +
                      std::to_string(c.x + 0.5 * c.side) + ", " + std::to_string(c.y + 0.5 * c.side) +
                      "); sizes must be positive");
    if (leaves.size() + stack.size() > params.max_num_vertices)
      throw Error(ErrorClass::meshing, kStage,
                  "the sizing asks for more than " + std::to_string(params.max_num_vertices) +
                      " vertices; simplify the domain or coarsen the sizing");
    double lo = e, hi = e;
    for (int q = 0; q < 4; ++q) {
      const double corner = size({c.x + (q & 1) * c.side, c.y + (q >> 1) * c.side});
      if (corner > 0.0) lo = std::min(lo, corner), hi = std::max(hi, corner);
    }
    if ((c.side > 8.0 * e || hi > 2.0 * lo) && c.side > 0.5 * lo && c.depth < 40) {
      const double h = 0.5 * c.side;
      for (int q = 3; q >= 0; --q) stack.push_back({c.x + (q & 1) * h, c.y + (q >> 1) * h, h, c.depth + 1});
      continue;
    }
    const double target = 0.95 * std::max(lo, 0.25 * e);
    const int kx = std::max(1, static_cast<int>(std::ceil(c.side / target)));
    const int ky = std::max(1, static_cast<int>(std::ceil(c.side / (0.866 * target))));
    const double dx = c.side / kx, dy = c.side / ky;
    for (int j = 0; j < ky; ++j)
      for (int i = 0; i < kx; ++i) {
        const double shift = (j % 2) ? 0.25 : -0.25;
        leaves.emplace_back(K::Point_2(c.x + (i + 0.5 + shift) * dx, c.y + (j + 0.5) * dy), dx);
      }
  }
  if (ct.number_of_vertices() + leaves.size() > params.max_num_vertices)
    throw Error(ErrorClass::meshing, kStage,
                "the sizing asks for more than " + std::to_string(params.max_num_vertices) +
                    " vertices; simplify the domain or coarsen the sizing");
  std::vector<K::Point_2> seeds;
  FaceHandle hint;
  for (const auto& [p, side] : leaves) {
    hint = ct.locate(p, hint);
    if (ct.is_infinite(hint) || !hint->is_in_domain()) continue;
    Search nearest(tree, p, 1);
    if (nearest.begin()->second < 0.36 * side * side) continue;
    seeds.push_back(p);
  }
  ct.insert(seeds.begin(), seeds.end());
}

// Indices of `points` in Hilbert curve order.
std::vector<std::size_t> hilbert_order(const std::vector<K::Point_2>& points) {
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Map = CGAL::Pointer_property_map<K::Point_2>::const_type;
  CGAL::hilbert_sort(order.begin(), order.end(),
                     CGAL::Spatial_sort_traits_adapter_2<K, Map>(CGAL::make_property_map(points)));
  return order;
}

std::string ring_name(int polygon, int ring) {
  return "polygon " + std::to_string(polygon) +
         (ring == 0 ? std::string(" outer ring") : " hole " + std::to_string(ring - 1));
}

// Signed turning angle at ring[k], degrees, positive for a left turn.
double turning_angle_deg(const Ring& ring, std::size_t k) {
  const std::size_t n = ring.size();
  const Point2& p = ring[(k + n - 1) % n];
  const Point2& q = ring[k];
  const Point2& r = ring[(k + 1) % n];
  const double ax = q.x - p.x, ay = q.y - p.y, bx = r.x - q.x, by = r.y - q.y;
  return std::atan2(ax * by - ay * bx, ax * bx + ay * by) * 180.0 / kPi;
}

void check_input(const Domain& domain, const BackgroundMeshParams& params) {
  if (!params.max_edge_m)
    throw Error(ErrorClass::internal, kStage, "no sizing oracle (max_edge_m) given");
  if (!(params.min_angle_deg >= 0.0 && params.min_angle_deg <= 20.7 + 1e-9))
    throw Error(ErrorClass::internal, kStage,
                "min_angle_deg must be in [0, 20.7] for refinement to terminate");
  if (domain.polygons.empty()) throw Error(ErrorClass::input, kStage, "the domain is empty");
  for (std::size_t p = 0; p < domain.polygons.size(); ++p) {
    const Polygon& poly = domain.polygons[p];
    for (std::size_t r = 0; r <= poly.holes.size(); ++r) {
      const Ring& ring = r == 0 ? poly.outer : poly.holes[r - 1];
      const std::string name = ring_name(static_cast<int>(p), static_cast<int>(r));
      if (ring.size() < 3)
        throw Error(ErrorClass::input, kStage, name + " has fewer than 3 vertices");
      for (const Point2& q : ring)
        if (!std::isfinite(q.x) || !std::isfinite(q.y))
          throw Error(ErrorClass::input, kStage, name + " has a non-finite coordinate");
      const double a = signed_area(ring);
      if (r == 0 ? !(a > 0.0) : !(a < 0.0))
        throw Error(ErrorClass::input, kStage,
                    name + (r == 0 ? " is not counter-clockwise" : " is not clockwise") +
                        " (orient the domain with orient_polygon first)");
    }
  }
}

}  // namespace

BackgroundMesh build_background_mesh(const Domain& domain, const BackgroundMeshParams& params) {
  check_input(domain, params);
  auto progress = [&params](double done) {
    if (params.progress) params.progress(done);
  };

  // --- Constrained Delaunay triangulation of all rings.
  struct RingRef {
    int polygon;
    int ring;
    const Ring* points;
    Ct::Constraint_id cid;
  };
  std::vector<RingRef> rings;
  for (std::size_t p = 0; p < domain.polygons.size(); ++p) {
    const Polygon& poly = domain.polygons[p];
    rings.push_back({static_cast<int>(p), 0, &poly.outer, nullptr});
    for (std::size_t h = 0; h < poly.holes.size(); ++h)
      rings.push_back({static_cast<int>(p), static_cast<int>(h + 1), &poly.holes[h], nullptr});
  }
  Ct ct;
  std::size_t num_input_vertices = 0;
  for (RingRef& r : rings) {
    std::vector<K::Point_2> pts;
    pts.reserve(r.points->size());
    for (const Point2& q : *r.points) pts.emplace_back(q.x, q.y);
    r.cid = ct.insert_constraint(pts.begin(), pts.end(), /*close=*/true);
    num_input_vertices += r.points->size();
  }
  // Crossings add vertices (Exact_predicates_tag computes intersections), repeated or
  // shared vertices merge, a vertex on another segment splits it: each breaks the
  // one-chain-per-ring structure, so the input must be a valid, simple domain.
  for (const RingRef& r : rings) {
    const std::size_t n = std::distance(ct.vertices_in_constraint_begin(r.cid),
                                        ct.vertices_in_constraint_end(r.cid));
    if (n != r.points->size() + 1)
      throw Error(ErrorClass::input, kStage,
                  ring_name(r.polygon, r.ring) +
                      " repeats a vertex, or crosses or touches a ring (itself or another)");
  }
  if (ct.number_of_vertices() != num_input_vertices)
    throw Error(ErrorClass::input, kStage, "the domain's rings cross, touch or share vertices");

  // --- Delaunay refinement inside the domain only.
  mark_domain(ct);
  // The flood follows the geometry, not the polygon structure: with a polygon inside
  // another one, or a hole outside its polygon, some ring has the domain on its right.
  for (const RingRef& r : rings) {
    auto it = ct.vertices_in_constraint_begin(r.cid);
    for (auto next = std::next(it); next != ct.vertices_in_constraint_end(r.cid); it = next++) {
      FaceHandle fh;
      int i = 0;
      if (!ct.is_edge(*it, *next, fh, i))
        throw Error(ErrorClass::internal, kStage, "a ring edge is missing from the triangulation");
      // In a CCW face, the edge opposite vertex i runs from vertex(ccw(i)) to vertex(cw(i)).
      FaceHandle left = fh->vertex(Ct::ccw(i)) == *it ? fh : fh->neighbor(i);
      FaceHandle right = left == fh ? fh->neighbor(i) : fh;
      if (!left->is_in_domain() || right->is_in_domain())
        throw Error(ErrorClass::input, kStage,
                    ring_name(r.polygon, r.ring) +
                        " does not bound the domain as its polygon says (a polygon inside "
                        "another one, or a hole outside its polygon)");
    }
  }
  progress(0.05);
  if (params.seed_interior) {
    seed_interior(ct, domain, params);
    mark_domain(ct);  // the faces made by the seeds have no flags yet
  }
  progress(kSeededShare);

  const double sine = std::sin(params.min_angle_deg * kPi / 180.0);
  const SizeAndAngleCriteria criteria(&params.max_edge_m, sine * sine);
  CGAL::Delaunay_mesher_2<Ct, SizeAndAngleCriteria> mesher(ct, criteria);
  try {
    mesher.init(/*domain_specified=*/true);
    // One point at a time, so that a runaway refinement is stopped. The seeds give most
    // vertices: the share of refinement done is told as if it added a fifth of them.
    const double seeded = static_cast<double>(ct.number_of_vertices());
    for (std::size_t step = 1; mesher.step_by_step_refine_mesh(); ++step) {
      if (ct.number_of_vertices() > params.max_num_vertices)
        throw Error(ErrorClass::meshing, kStage,
                    "refinement exceeded " + std::to_string(params.max_num_vertices) +
                        " vertices; simplify the domain or coarsen the sizing");
      if (step % 4096 == 0)
        progress(kSeededShare +
                 (kRefinedShare - kSeededShare) *
                     std::min(0.95, (ct.number_of_vertices() - seeded) / (0.2 * seeded + 1.0)));
    }
    progress(kRefinedShare);
  } catch (const CGAL::Failure_exception& e) {
    throw Error(ErrorClass::meshing, kStage,
                "CGAL's Delaunay refinement failed after " +
                    std::to_string(ct.number_of_vertices()) + " vertices (" + e.expression() +
                    " in " + e.filename() + ":" + std::to_string(e.line_number()) +
                    "): a known CGAL failure where a boundary vertex lies very close to "
                    "another boundary segment; a larger --min-width or --simplify avoids it");
  }

  // --- Flat arrays, vertices and triangles in Hilbert curve order: later stages walk
  // the mesh by adjacency (floods, smoothing), and neighbours close in memory keep that
  // cache-friendly. The median policy is deterministic.
  // The sort keys and orders are freed as soon as read: at this point the triangulation
  // holds most of the memory, and they would add to the peak beside the flat arrays.
  BackgroundMesh mesh;
  std::vector<FaceHandle> domain_faces;
  {
    std::vector<VertexHandle> used_vertices;
    for (auto v = ct.finite_vertices_begin(); v != ct.finite_vertices_end(); ++v) v->info() = -1;
    for (auto f = ct.finite_faces_begin(); f != ct.finite_faces_end(); ++f) {
      f->info().id = -1;
      if (!f->is_in_domain()) continue;
      domain_faces.push_back(f);
      for (int i = 0; i < 3; ++i) {
        if (f->vertex(i)->info() == -1) used_vertices.push_back(f->vertex(i));
        f->vertex(i)->info() = 0;
      }
    }
    std::vector<K::Point_2> keys;
    keys.reserve(used_vertices.size());
    for (VertexHandle v : used_vertices) keys.push_back(v->point());
    const std::vector<std::size_t> vertex_order = hilbert_order(keys);
    mesh.points.resize(used_vertices.size());
    for (std::size_t k = 0; k < vertex_order.size(); ++k) {
      VertexHandle v = used_vertices[vertex_order[k]];
      v->info() = static_cast<int>(k);
      mesh.points[k] = {v->point().x(), v->point().y()};
    }
  }
  {
    std::vector<K::Point_2> keys;
    keys.reserve(domain_faces.size());
    for (FaceHandle f : domain_faces)
      keys.push_back(
          CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()));
    const std::vector<std::size_t> face_order = hilbert_order(keys);
    for (std::size_t k = 0; k < face_order.size(); ++k)
      domain_faces[face_order[k]]->info().id = static_cast<int>(k);
  }
  const int num_faces = static_cast<int>(domain_faces.size());
  std::vector<FaceHandle>().swap(domain_faces);
  mesh.triangles.resize(num_faces);
  mesh.neighbours.resize(num_faces);
  for (auto f = ct.finite_faces_begin(); f != ct.finite_faces_end(); ++f) {
    const int id = f->info().id;
    if (id < 0) continue;
    for (int i = 0; i < 3; ++i) {
      mesh.triangles[id][i] = f->vertex(i)->info();
      FaceHandle n = f->neighbor(i);
      mesh.neighbours[id][i] = ct.is_infinite(n) ? -1 : n->info().id;
    }
  }

  // --- Boundary chains, read from the constraints that refinement split.
  mesh.boundary_chain_of_vertex.assign(mesh.points.size(), -1);
  const double corner_deg = params.corner_angle_deg;
  for (const RingRef& r : rings) {
    BoundaryChain chain;
    chain.polygon = r.polygon;
    chain.ring = r.ring;
    const Ring& ring = *r.points;
    std::size_t next_input = 0;  // the next input vertex expected along the chain
    for (auto it = ct.vertices_in_constraint_begin(r.cid); it != ct.vertices_in_constraint_end(r.cid);
         ++it) {
      const int id = (*it)->info();
      if (!chain.vertices.empty() && id == chain.vertices.front()) break;  // closing vertex
      if (id < 0)
        throw Error(ErrorClass::internal, kStage, "a boundary vertex is not in the domain");
      const bool is_input = next_input < ring.size() && (*it)->point().x() == ring[next_input].x &&
                            (*it)->point().y() == ring[next_input].y;
      const double turn = is_input ? turning_angle_deg(ring, next_input) : 0.0;
      if (is_input) ++next_input;
      chain.vertices.push_back(id);
      chain.turning_angle_deg.push_back(turn);
      chain.is_corner.push_back(std::abs(turn) > corner_deg ? 1 : 0);
      chain.corner_turning_deg.push_back(std::abs(turn) > corner_deg ? turn : 0.0);
      chain.is_input_vertex.push_back(is_input ? 1 : 0);
    }
    if (next_input != ring.size())
      throw Error(ErrorClass::internal, kStage,
                  ring_name(r.polygon, r.ring) + ": the boundary chain lost input vertices");
    const std::size_t n = chain.vertices.size();
    chain.arc_length_m.resize(n);
    double s = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      chain.arc_length_m[k] = s;
      const Point2& a = mesh.points[chain.vertices[k]];
      const Point2& b = mesh.points[chain.vertices[(k + 1) % n]];
      s += std::hypot(b.x - a.x, b.y - a.y);
    }
    chain.length_m = s;
    const int chain_id = static_cast<int>(mesh.chains.size());
    for (int v : chain.vertices) {
      if (mesh.boundary_chain_of_vertex[v] != -1)
        throw Error(ErrorClass::internal, kStage, "a vertex lies on two boundary chains");
      mesh.boundary_chain_of_vertex[v] = chain_id;
    }
    mesh.chains.push_back(std::move(chain));
  }

  validate_background_mesh(mesh);
  // The marked faces must cover the domain exactly.
  const double mesh_area_m2 = area(mesh);
  const double domain_area_m2 = area(domain);
  if (std::abs(mesh_area_m2 - domain_area_m2) > 1e-6 * domain_area_m2)
    throw Error(ErrorClass::internal, kStage,
                "the triangles do not cover the domain (meshed area " +
                    std::to_string(mesh_area_m2) + " m2, domain area " +
                    std::to_string(domain_area_m2) + " m2)");
  return mesh;
}

double area(const BackgroundMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles)
    sum += signed_area(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
  return sum;
}

void validate_background_mesh(const BackgroundMesh& mesh) {
  const auto fail = [](const std::string& what) {
    throw Error(ErrorClass::internal, kStage, "invalid background mesh: " + what);
  };
  const int num_points = static_cast<int>(mesh.points.size());
  const int num_triangles = static_cast<int>(mesh.triangles.size());
  if (mesh.neighbours.size() != mesh.triangles.size()) fail("#neighbours != #triangles");
  if (mesh.boundary_chain_of_vertex.size() != mesh.points.size())
    fail("#boundary_chain_of_vertex != #points");

  // Directed boundary edges (a, b) -> count; each must match one chain edge exactly.
  std::map<std::pair<int, int>, int> boundary_edges;
  for (int f = 0; f < num_triangles; ++f) {
    const auto& t = mesh.triangles[f];
    for (int i = 0; i < 3; ++i)
      if (t[i] < 0 || t[i] >= num_points) fail("vertex id out of range");
    const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    if (!((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) > 0.0))
      fail("triangle " + std::to_string(f) + " is not counter-clockwise");
    for (int i = 0; i < 3; ++i) {
      const int u = t[(i + 1) % 3], w = t[(i + 2) % 3];
      const int g = mesh.neighbours[f][i];
      if (g == -1) {
        if (++boundary_edges[{u, w}] > 1) fail("a boundary edge appears twice");
        continue;
      }
      if (g < 0 || g >= num_triangles || g == f) fail("neighbour id out of range");
      const auto& s = mesh.triangles[g];
      bool ok = false;
      for (int j = 0; j < 3; ++j)
        if (s[(j + 1) % 3] == w && s[(j + 2) % 3] == u && mesh.neighbours[g][j] == f) ok = true;
      if (!ok) fail("neighbours of triangles " + std::to_string(f) + " and " + std::to_string(g) +
                    " are not symmetric");
    }
  }
  std::size_t num_chain_edges = 0;
  for (std::size_t c = 0; c < mesh.chains.size(); ++c) {
    const BoundaryChain& chain = mesh.chains[c];
    const std::size_t n = chain.vertices.size();
    if (n < 3 || chain.arc_length_m.size() != n || chain.is_corner.size() != n ||
        chain.turning_angle_deg.size() != n || chain.is_input_vertex.size() != n)
      fail("chain " + std::to_string(c) + " has inconsistent sizes");
    for (std::size_t k = 0; k < n; ++k) {
      const int a = chain.vertices[k], b = chain.vertices[(k + 1) % n];
      if (a < 0 || a >= num_points || mesh.boundary_chain_of_vertex[a] != static_cast<int>(c))
        fail("chain " + std::to_string(c) + " vertex mismatch");
      // Domain on the left of a -> b means a CCW triangle holds the directed edge a -> b.
      if (boundary_edges.find({a, b}) == boundary_edges.end())
        fail("chain " + std::to_string(c) + " edge is not a boundary edge with the domain on its left");
    }
    num_chain_edges += n;
  }
  if (num_chain_edges != boundary_edges.size())
    fail("boundary edges that belong to no chain");
}

VertexTriangles vertex_triangles(const BackgroundMesh& mesh) {
  VertexTriangles vt;
  vt.offset.assign(mesh.points.size() + 1, 0);
  for (const auto& t : mesh.triangles)
    for (int v : t) ++vt.offset[v + 1];
  for (std::size_t v = 0; v < mesh.points.size(); ++v) vt.offset[v + 1] += vt.offset[v];
  vt.triangles.resize(vt.offset.back());
  std::vector<int> fill(vt.offset.begin(), vt.offset.end() - 1);
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f)
    for (int v : mesh.triangles[f]) vt.triangles[fill[v]++] = f;
  return vt;
}

}  // namespace isoquad
