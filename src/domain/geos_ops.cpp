#include "domain/geos_ops.h"

#include <geos_c.h>

#include "core/error.h"

namespace isoquad {

struct GeosState {
  GEOSContextHandle_t handle = nullptr;
  std::string last_error;
};

namespace {

void error_handler_r(const char* message, void* userdata) {
  static_cast<GeosState*>(userdata)->last_error = message ? message : "";
}

}  // namespace

GeosGeometry::GeosGeometry(GeosGeometry&& o) noexcept : state_(o.state_), geom_(o.geom_) {
  o.geom_ = nullptr;
}

GeosGeometry& GeosGeometry::operator=(GeosGeometry&& o) noexcept {
  if (this != &o) {
    if (geom_) GEOSGeom_destroy_r(state_->handle, static_cast<GEOSGeometry*>(geom_));
    state_ = o.state_;
    geom_ = o.geom_;
    o.geom_ = nullptr;
  }
  return *this;
}

GeosGeometry::~GeosGeometry() {
  if (geom_) GEOSGeom_destroy_r(state_->handle, static_cast<GEOSGeometry*>(geom_));
}

void* GeosGeometry::release() {
  void* g = geom_;
  geom_ = nullptr;
  return g;
}

GeosContext::GeosContext() : state_(std::make_unique<GeosState>()) {
  state_->handle = GEOS_init_r();
  GEOSContext_setErrorMessageHandler_r(state_->handle, error_handler_r, state_.get());
  GEOSContext_setNoticeMessageHandler_r(state_->handle, nullptr, nullptr);
}

GeosContext::~GeosContext() {
  GEOS_finish_r(state_->handle);
}

GeosGeometry GeosContext::check(void* g, const char* what) {
  if (!g)
    throw Error(ErrorClass::meshing, "geometry",
                std::string("GEOS ") + what + " failed: " + state_->last_error);
  return GeosGeometry(state_.get(), g);
}

GeosGeometry GeosContext::polygon_with_holes(const Polygon& p) {
  std::vector<Ring> rings{p.outer};
  rings.insert(rings.end(), p.holes.begin(), p.holes.end());
  return polygon(rings);
}

GeosGeometry GeosContext::domain_multipolygon(const Domain& d) {
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : d.polygons) parts.push_back(polygon_with_holes(p));
  return multipolygon(std::move(parts));
}

GeosGeometry GeosContext::polygon(const std::vector<Ring>& rings) {
  GEOSContextHandle_t h = state_->handle;
  std::vector<GEOSGeometry*> lrs;
  for (const Ring& r : rings) {
    const unsigned n = static_cast<unsigned>(r.size());
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, n + 1, 2);
    for (unsigned i = 0; i <= n; ++i) {
      const Point2& p = r[i % n];
      GEOSCoordSeq_setXY_r(h, seq, i, p.x, p.y);
    }
    GEOSGeometry* lr = GEOSGeom_createLinearRing_r(h, seq);
    if (!lr) {
      for (GEOSGeometry* g : lrs) GEOSGeom_destroy_r(h, g);
      throw Error(ErrorClass::input, "geometry", "invalid ring: " + state_->last_error);
    }
    lrs.push_back(lr);
  }
  if (lrs.empty()) return check(GEOSGeom_createEmptyPolygon_r(h), "empty polygon");
  GEOSGeometry* shell = lrs[0];
  GEOSGeometry* poly =
      GEOSGeom_createPolygon_r(h, shell, lrs.data() + 1, static_cast<unsigned>(lrs.size() - 1));
  return check(poly, "polygon");
}

GeosGeometry GeosContext::gather(std::vector<GeosGeometry> parts, int type, const char* what) {
  std::vector<GEOSGeometry*> gs;
  for (GeosGeometry& p : parts) gs.push_back(static_cast<GEOSGeometry*>(p.release()));
  return check(GEOSGeom_createCollection_r(state_->handle, type, gs.data(),
                                           static_cast<unsigned>(gs.size())),
               what);
}

GeosGeometry GeosContext::multipolygon(std::vector<GeosGeometry> parts) {
  return gather(std::move(parts), GEOS_MULTIPOLYGON, "multipolygon");
}

GeosGeometry GeosContext::collection(std::vector<GeosGeometry> parts) {
  return gather(std::move(parts), GEOS_GEOMETRYCOLLECTION, "collection");
}

bool GeosContext::is_empty(const GeosGeometry& g) {
  return GEOSisEmpty_r(state_->handle, static_cast<GEOSGeometry*>(g.get())) == 1;
}

GeosGeometry GeosContext::translated(const GeosGeometry& g, double dx) {
  std::vector<GeosGeometry> parts;
  for (Polygon& p : polygons(g)) {
    std::vector<Ring> rings{std::move(p.outer)};
    for (Ring& h : p.holes) rings.push_back(std::move(h));
    for (Ring& r : rings)
      for (Point2& q : r) q.x += dx;
    parts.push_back(polygon(rings));
  }
  return multipolygon(std::move(parts));
}

GeosValidity GeosContext::validity(const GeosGeometry& g) {
  GeosValidity v;
  char* reason = nullptr;
  GEOSGeometry* location = nullptr;
  const char ok = GEOSisValidDetail_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), 0,
                                      &reason, &location);
  if (ok == 2) throw Error(ErrorClass::internal, "geometry", "GEOS validity check failed");
  v.valid = ok == 1;
  if (reason) {
    v.reason = reason;
    GEOSFree_r(state_->handle, reason);
  }
  if (location) {
    GEOSGeomGetX_r(state_->handle, location, &v.location.x);
    GEOSGeomGetY_r(state_->handle, location, &v.location.y);
    GEOSGeom_destroy_r(state_->handle, location);
  }
  return v;
}

GeosGeometry GeosContext::make_valid(const GeosGeometry& g) {
  GEOSContextHandle_t h = state_->handle;
  GEOSMakeValidParams* params = GEOSMakeValidParams_create_r(h);
  GEOSMakeValidParams_setMethod_r(h, params, GEOS_MAKE_VALID_STRUCTURE);
  GEOSMakeValidParams_setKeepCollapsed_r(h, params, 0);
  GEOSGeometry* out = GEOSMakeValidWithParams_r(h, static_cast<GEOSGeometry*>(g.get()), params);
  GEOSMakeValidParams_destroy_r(h, params);
  GeosGeometry fixed = check(out, "make-valid");
  // Keep the polygons only (collapsed parts come back as lines or points).
  std::vector<Polygon> polys = polygons(fixed);
  std::vector<GeosGeometry> parts;
  for (const Polygon& p : polys) {
    std::vector<Ring> rings{p.outer};
    rings.insert(rings.end(), p.holes.begin(), p.holes.end());
    parts.push_back(polygon(rings));
  }
  return multipolygon(std::move(parts));
}

GeosGeometry GeosContext::unary_union(const GeosGeometry& g) {
  return check(GEOSUnaryUnion_r(state_->handle, static_cast<GEOSGeometry*>(g.get())), "union");
}

GeosGeometry GeosContext::unary_union_snapped(const GeosGeometry& g, double grid) {
  return check(GEOSUnaryUnionPrec_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), grid),
               "union");
}

GeosGeometry GeosContext::snapped(const GeosGeometry& g, double grid) {
  return check(GEOSGeom_setPrecision_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), grid, 0),
               "snap");
}

GeosGeometry GeosContext::union_of(const GeosGeometry& a, const GeosGeometry& b) {
  return check(GEOSUnion_r(state_->handle, static_cast<GEOSGeometry*>(a.get()),
                           static_cast<GEOSGeometry*>(b.get())),
               "union");
}

GeosGeometry GeosContext::intersection(const GeosGeometry& a, const GeosGeometry& b) {
  return check(GEOSIntersection_r(state_->handle, static_cast<GEOSGeometry*>(a.get()),
                                  static_cast<GEOSGeometry*>(b.get())),
               "intersection");
}

GeosGeometry GeosContext::clone(const GeosGeometry& g) {
  return check(GEOSGeom_clone_r(state_->handle, static_cast<GEOSGeometry*>(g.get())), "clone");
}

GeosGeometry GeosContext::sym_difference(const GeosGeometry& a, const GeosGeometry& b) {
  return check(GEOSSymDifference_r(state_->handle, static_cast<GEOSGeometry*>(a.get()),
                                   static_cast<GEOSGeometry*>(b.get())),
               "symmetric difference");
}

GeosGeometry GeosContext::difference(const GeosGeometry& a, const GeosGeometry& b) {
  return check(GEOSDifference_r(state_->handle, static_cast<GEOSGeometry*>(a.get()),
                                static_cast<GEOSGeometry*>(b.get())),
               "difference");
}

bool GeosContext::intersects(const GeosGeometry& a, const GeosGeometry& b) {
  const char r = GEOSIntersects_r(state_->handle, static_cast<GEOSGeometry*>(a.get()),
                                  static_cast<GEOSGeometry*>(b.get()));
  if (r == 2) check(nullptr, "intersects");
  return r == 1;
}

GeosGeometry GeosContext::clip_by_rect(const GeosGeometry& g, double xmin, double ymin, double xmax,
                                       double ymax) {
  return check(
      GEOSClipByRect_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), xmin, ymin, xmax, ymax),
      "clip");
}

GeosGeometry GeosContext::clip_valid(const GeosGeometry& g, double xmin, double ymin, double xmax,
                                     double ymax) {
  GeosGeometry clipped = clip_by_rect(g, xmin, ymin, xmax, ymax);
  if (validity(clipped).valid) return clipped;
  return intersection(g, polygon({{{xmin, ymin}, {xmax, ymin}, {xmax, ymax}, {xmin, ymax}}}));
}

GeosGeometry GeosContext::buffer_mitre(const GeosGeometry& g, double distance, double mitre_limit) {
  return check(GEOSBufferWithStyle_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), distance,
                                     8, GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, mitre_limit),
               "buffer");
}

namespace {

Ring ring_points(GEOSContextHandle_t h, const GEOSGeometry* lr) {
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(h, lr);
  unsigned n = 0;
  GEOSCoordSeq_getSize_r(h, seq, &n);
  Ring r;
  r.reserve(n);
  for (unsigned i = 0; i < n; ++i) {
    double x = 0, y = 0;
    GEOSCoordSeq_getXY_r(h, seq, i, &x, &y);
    r.push_back({x, y});
  }
  if (r.size() > 1 && r.front() == r.back()) r.pop_back();
  return r;
}

void collect(GEOSContextHandle_t h, const GEOSGeometry* g, std::vector<Polygon>& out) {
  const int type = GEOSGeomTypeId_r(h, g);
  if (type == GEOS_POLYGON) {
    if (GEOSisEmpty_r(h, g)) return;
    Polygon p;
    p.outer = ring_points(h, GEOSGetExteriorRing_r(h, g));
    const int nh = GEOSGetNumInteriorRings_r(h, g);
    for (int i = 0; i < nh; ++i) p.holes.push_back(ring_points(h, GEOSGetInteriorRingN_r(h, g, i)));
    out.push_back(std::move(p));
  } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(h, g);
    for (int i = 0; i < n; ++i) collect(h, GEOSGetGeometryN_r(h, g, i), out);
  }
}

}  // namespace

std::vector<Polygon> GeosContext::polygons(const GeosGeometry& g) {
  std::vector<Polygon> out;
  collect(state_->handle, static_cast<const GEOSGeometry*>(g.get()), out);
  return out;
}

double GeosContext::area(const GeosGeometry& g) {
  double a = 0.0;
  GEOSArea_r(state_->handle, static_cast<GEOSGeometry*>(g.get()), &a);
  return a;
}

}  // namespace isoquad
