// Rings that touch at a point. GEOS (and the OGC model) allows a hole to touch its
// shell or another hole at one vertex, and water domains cut from coastlines often have
// such pinch points; the background mesh cannot triangulate a domain pinched to a point.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace isoquad {

// Places where the domain's rings touch, one point each: a vertex used twice (by two
// rings, or twice by one ring), or within 1e-9 of the domain's extent of a segment it
// does not end.
std::vector<Point2> pinch_points(const Domain& domain);

// Boundaries that coincide along a stretch, within rounding: polygons that overlap or
// share boundary (the pieces of a land mass that the source cuts at the antimeridian
// meet only once projected: Chukotka round the North Pole), and a ring running back
// along itself (a bbox round every longitude: its two sides at -180 and 180 become one
// meridian once projected). Merged by a union (each polygon made valid first) with
// coordinates snapped to a grid of 4e-9 of the domain's extent. Polygons or rings
// touching only at points stay as they are, and the domain is unchanged unless polygons
// join or fewer places touch. Returns whether it changed.
bool merge_shared_boundaries(Domain& domain);

// Separates the rings at every pinch point by cutting a small octagon of radius r out of
// the domain there: two holes touching at a point become one hole, a hole touching its
// shell becomes a bay. Pieces and holes the cut leaves smaller than r^2 (slivers where a
// thin spike met the octagon, which would touch themselves within rounding) are dropped.
// Throws Error(input) when nothing is left.
void separate_rings(Domain& domain, double r_m);

// Closes gaps and slits of the domain narrower than 2 r (a closing: offset out by r, then
// in, with mitred corners): polygons that should meet but miss by a hair (tiles or
// neighbours digitised less than a millimetre apart) leave slits whose sides touch where
// separate_rings cannot part them.
void close_hairline_gaps(Domain& domain, double r_m);

}  // namespace isoquad
