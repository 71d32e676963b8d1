// Plain planar geometry shared by every stage: points, rings, polygons, domains.
#pragma once

#include <cmath>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace isoquad {

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

inline bool operator==(const Point2& a, const Point2& b) { return a.x == b.x && a.y == b.y; }
inline bool operator!=(const Point2& a, const Point2& b) { return !(a == b); }

// |(x, y)| without std::hypot's overflow care, which costs several times more; for
// metre coordinates in the hot loops (lengths, convexity, mean value weights).
inline double length(double x, double y) { return std::sqrt(x * x + y * y); }
inline double distance(const Point2& a, const Point2& b) { return length(b.x - a.x, b.y - a.y); }

// A ring is stored open: the last point is NOT a copy of the first.
using Ring = std::vector<Point2>;

// Outer ring counter-clockwise, holes clockwise (after orient_polygon()).
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

// A planar domain: one or more disjoint polygons (components), all in one CRS.
struct Domain {
  std::vector<Polygon> polygons;
  std::string crs_wkt;   // WKT2 of the CRS the coordinates are in
  std::string crs_name;  // a human-readable name of that CRS
};

// Bounding boxes {xmin, ymin, xmax, ymax}: of a domain (its outer rings), of points.
std::array<double, 4> bounding_box(const Domain& domain);
std::array<double, 4> bounding_box(const std::vector<Point2>& points);

// Signed area of a ring (positive when counter-clockwise), shoelace formula.
double signed_area(const Ring& ring);
// Signed area of the triangle a, b, c (positive when counter-clockwise).
inline double signed_area(const Point2& a, const Point2& b, const Point2& c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
// Length of the closed ring.
double perimeter(const Ring& ring);
// Length of the open polyline (its points in order; the last not joined to the first).
double polyline_length(const std::vector<Point2>& line);
// Area of the polygon: outer area minus the holes' areas (unsigned).
double area(const Polygon& polygon);
double area(const Domain& domain);
double perimeter(const Polygon& polygon);
double perimeter(const Domain& domain);
// Whether a ray from p towards +x crosses the ring's sides an odd number of times (its
// last point joined to its first; a ring that repeats its first point alike): the
// even-odd rule, p inside when the count over all the rings that bound an area is odd.
bool crosses_odd(const std::vector<Point2>& ring, const Point2& p);
// A ring's sides in bands of y (about eight to a band), for the questions of many points
// about one ring in time proportional to the sides that cross the point's band. The ring
// must outlive it.
class EdgeBands {
 public:
  explicit EdgeBands(const std::vector<Point2>& ring);
  // The sides (side i joins points i and i + 1, the last the first) whose y range meets
  // the band of y: every side with y between its ends' y; none outside the ring's range.
  std::pair<const std::size_t*, const std::size_t*> sides_at(double y) const;
  // crosses_odd(ring, p), the same answer.
  bool crosses_odd(const Point2& p) const;

 private:
  std::size_t band(double y) const;
  const std::vector<Point2>& ring_;
  double y0_ = 0, y1_ = 0;
  std::size_t bands_ = 1;
  std::vector<std::size_t> start_, sides_;
};
// Whether p lies inside the domain (even-odd over every ring: in a polygon, not in its
// holes); a point on the boundary may go either way.
bool domain_contains(const Domain& domain, const Point2& p);
// The distance from p to the domain's boundary (its nearest ring; infinity without one).
double distance_to_boundary(const Domain& domain, const Point2& p);
// Calls visit(a, b) for each side of every ring of the domain (each polygon's outer ring,
// then its holes; a ring's closing side last), in that order.
template <typename Visit>
void for_each_side(const Domain& domain, Visit visit) {
  auto ring_sides = [&visit](const Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) visit(r[i], r[(i + 1) % r.size()]);
  };
  for (const Polygon& polygon : domain.polygons) {
    ring_sides(polygon.outer);
    for (const Ring& hole : polygon.holes) ring_sides(hole);
  }
}
std::size_t num_vertices(const Polygon& polygon);
std::size_t num_vertices(const Domain& domain);
std::size_t num_holes(const Domain& domain);

// Makes the outer ring counter-clockwise and the holes clockwise.
void orient_polygon(Polygon& polygon);

// Rotates the ring to start at its lowest vertex (least y, then least x).
void start_at_lowest_vertex(Ring& ring);

// Removes consecutive duplicate points (including a closing copy of the first point)
// and spikes (a vertex where the ring turns back on itself: prev == next). Returns the
// number of points removed.
std::size_t remove_duplicates_and_spikes(Ring& ring);
// The same on every ring of the polygons; then holes left with fewer than 3 points are
// dropped, and polygons whose outer ring is.
void remove_duplicates_and_spikes(std::vector<Polygon>& polygons);

// "(x, y)" with 10 significant digits, for messages.
std::string format_point(const Point2& p);

// Sorts components by decreasing area, ties broken by the first vertex, so that the
// order is deterministic and the largest comes first.
void sort_by_area(std::vector<Polygon>& polygons);

// The form every planar domain's polygons take: duplicate points and spikes removed
// (remove_duplicates_and_spikes), outer rings counter-clockwise and holes clockwise,
// each ring from its lowest vertex (so that nothing depends on where a source drew its
// rings from), sorted by area.
void normalize_polygons(std::vector<Polygon>& polygons);

// Polylines (a closed one repeats its first point at the end), indexed by runs of
// segments with their bounding boxes in a uniform grid, for "is this point near them"
// queries. `slack` (empty, or one per line) widens the tolerance of each line by its
// own amount.
class PolylineIndex {
 public:
  explicit PolylineIndex(std::vector<std::vector<Point2>> lines = {},
                         std::vector<double> slack = {});
  bool empty() const { return lines_.empty(); }
  // Whether p lies within `tolerance` (plus the line's slack) of a segment.
  bool near(const Point2& p, double tolerance) const;
  // The segment nearest p within `tolerance` (plus its line's slack), as its two ends
  // in a and b; false when there is none. Of segments as near, the first line's, then
  // the first segment's.
  bool nearest_segment(const Point2& p, double tolerance, Point2& a, Point2& b) const;
  // The same segment as its line and index (segment k joins points k and k + 1 of the
  // line) with its distance to p; line -1 when there is none.
  struct Nearest {
    int line = -1, segment = -1;
    double distance = 0.0;
  };
  Nearest nearest(const Point2& p, double tolerance) const;
  // Every segment within `tolerance` (plus its line's slack) of p, as (line, segment),
  // in that order, each once.
  std::vector<std::pair<int, int>> segments_near(const Point2& p, double tolerance) const;

 private:
  // Calls visit(line, segment, distance) for each segment within `tolerance` (plus its
  // line's slack) of p, in the cells' order (a segment may come more than once), until
  // visit returns false.
  template <typename Visit>
  void visit_near(const Point2& p, double tolerance, Visit visit) const;
  struct Run {
    int line = 0, first = 0, last = 0;  // segments first .. last - 1 of the line
    double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  };
  std::vector<std::vector<Point2>> lines_;
  std::vector<double> slack_;
  std::vector<Run> runs_;
  // Grid of cells over the runs' boxes (widened by their slack): cell (i, j) lists the
  // runs whose box meets it, in cell_runs_[cell_start_[c] .. cell_start_[c + 1]).
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  double max_slack_ = 0;
  std::vector<int> cell_start_, cell_runs_;
};

// The point of the segment ab nearest p, and the distance from p to it.
Point2 nearest_on_segment(const Point2& p, const Point2& a, const Point2& b);
double distance_to_segment(const Point2& p, const Point2& a, const Point2& b);

}  // namespace isoquad
