// Planar boolean operations and validity checks, done by GEOS (through its C API).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct GeosState;

// A polygonal geometry owned by a GeosContext. Move-only.
class GeosGeometry {
 public:
  GeosGeometry() = default;
  GeosGeometry(GeosState* state, void* geom) : state_(state), geom_(geom) {}
  GeosGeometry(GeosGeometry&& o) noexcept;
  GeosGeometry& operator=(GeosGeometry&& o) noexcept;
  ~GeosGeometry();
  void* get() const { return geom_; }
  void* release();

 private:
  GeosState* state_ = nullptr;
  void* geom_ = nullptr;
};

// The validity problem of a geometry, when there is one.
struct GeosValidity {
  bool valid = true;
  std::string reason;  // e.g. "Self-intersection"
  Point2 location;
};

// One GEOS context (reentrant API); not shared between threads.
class GeosContext {
 public:
  GeosContext();
  ~GeosContext();
  GeosContext(const GeosContext&) = delete;
  GeosContext& operator=(const GeosContext&) = delete;

  // Rings as given (open); orientation does not matter to GEOS.
  GeosGeometry polygon(const std::vector<Ring>& rings);
  GeosGeometry multipolygon(std::vector<GeosGeometry> parts);
  // A polygon of the domain (its outer ring and holes), and the whole domain as one
  // multipolygon.
  GeosGeometry polygon_with_holes(const Polygon& p);
  GeosGeometry domain_multipolygon(const Domain& d);
  // Any geometries (polygons, multipolygons) as one collection, e.g. to union them.
  GeosGeometry collection(std::vector<GeosGeometry> parts);
  bool is_empty(const GeosGeometry& g);
  // A copy owned by this context (geometries are read by one thread at a time: a copy
  // lets another thread, with its own context, work on the same shape).
  GeosGeometry clone(const GeosGeometry& g);
  // The polygons of g moved by dx along x.
  GeosGeometry translated(const GeosGeometry& g, double dx);
  GeosValidity validity(const GeosGeometry& g);
  // GEOS's MakeValid (structure method), keeping only the polygonal part.
  GeosGeometry make_valid(const GeosGeometry& g);
  GeosGeometry unary_union(const GeosGeometry& g);
  // The union with every coordinate snapped to a grid of this spacing (GEOS's precision
  // model): pieces closer than about the spacing join.
  GeosGeometry unary_union_snapped(const GeosGeometry& g, double grid);
  // Every coordinate snapped to a grid of this spacing, the result made valid: parts
  // that collapse (a slit whose sides meet on the grid) are dropped. `g` must be valid.
  GeosGeometry snapped(const GeosGeometry& g, double grid);
  GeosGeometry union_of(const GeosGeometry& a, const GeosGeometry& b);
  GeosGeometry intersection(const GeosGeometry& a, const GeosGeometry& b);
  GeosGeometry difference(const GeosGeometry& a, const GeosGeometry& b);
  GeosGeometry sym_difference(const GeosGeometry& a, const GeosGeometry& b);
  bool intersects(const GeosGeometry& a, const GeosGeometry& b);
  // Offset by `distance` (negative: inwards) with mitred joins, so that corners keep
  // their place (down to mitre_limit, in multiples of |distance|) instead of rounding.
  GeosGeometry buffer_mitre(const GeosGeometry& g, double distance, double mitre_limit);
  // The part of g inside the rectangle (xmin, ymin, xmax, ymax); fast, possibly invalid
  // along the cut: overlays (intersection...) refuse such input.
  GeosGeometry clip_by_rect(const GeosGeometry& g, double xmin, double ymin, double xmax,
                            double ymax);
  // The same for a valid g, valid: the fast clip, or where that is invalid, the
  // intersection with the rectangle.
  GeosGeometry clip_valid(const GeosGeometry& g, double xmin, double ymin, double xmax,
                          double ymax);
  // The polygons of a (multi)polygon or collection, each with its rings, open.
  std::vector<Polygon> polygons(const GeosGeometry& g);
  double area(const GeosGeometry& g);

 private:
  GeosGeometry check(void* g, const char* what);
  // A GEOS collection of the given type (GEOS_MULTIPOLYGON...) owning the parts.
  GeosGeometry gather(std::vector<GeosGeometry> parts, int type, const char* what);
  std::unique_ptr<GeosState> state_;
};

}  // namespace isoquad
