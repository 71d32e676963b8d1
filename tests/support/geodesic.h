// Ellipsoidal reference areas for the projection tests (GeographicLib, WGS 84).
#pragma once

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <cmath>

#include "core/geometry.h"

namespace isoquad::test {

// Area in m2 of a lon/lat ring (degrees) on the WGS 84 ellipsoid, unsigned.
inline double geodesic_area_m2(const Ring& lonlat) {
  GeographicLib::PolygonArea poly(GeographicLib::Geodesic::WGS84());
  for (const Point2& p : lonlat) poly.AddPoint(p.y, p.x);
  double perimeter = 0, area = 0;
  poly.Compute(false, true, perimeter, area);
  return std::abs(area);
}

inline double geodesic_area_m2(const Polygon& lonlat) {
  double a = geodesic_area_m2(lonlat.outer);
  for (const Ring& h : lonlat.holes) a -= geodesic_area_m2(h);
  return a;
}

}  // namespace isoquad::test
