// Removing features narrower than the mesh can follow: a morphological opening then a
// closing of the domain by a disc of diameter min_width (GEOS offsets with mitred joins,
// so corners wider than the mitre limit keep their place). The opening takes off spikes
// of the domain narrower than min_width, the closing fills its notches and slits
// narrower than min_width; pieces that would change the topology stay (see below).
//
// Why: tiles are two element sizes wide. A slit of water a few hundred metres wide cut
// into land meshed at kilometres is a part of the boundary that tiles on both of its
// banks reach round, and the quads of such a tile fold across it. The automatic sizing
// already ignores channels narrower than about 2 hmin (feature_size.h); removing them
// from the domain keeps the geometry consistent with the sizes.
#pragma once

#include <cstddef>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct NarrowParams {
  double min_width_m = 0.0;  // 0: off
  double mitre_limit = 5.0;  // corners sharper than 2 asin(1 / limit) (23 deg) are bevelled
  // Up to this many candidate pieces, each is checked by applying it to the whole domain;
  // beyond, by counting where it touches the rest of the domain (see the .cpp).
  std::size_t max_sequential_pieces = 100;
};

// Where a piece lies and how narrow it is (twice its area over its perimeter: a strip's
// width), for the messages.
struct NarrowPlace {
  Point2 at;  // the mean of the piece's outer vertices
  double width_m = 0.0;
};
NarrowPlace place_of(const Polygon& piece);

struct NarrowResult {
  double area_removed_m2 = 0.0;  // by the opening (spikes, isthmuses)
  double area_added_m2 = 0.0;    // by the closing (notches, slits, narrow gaps)
  std::size_t num_pieces = 0;       // pieces removed or filled in
  std::size_t num_pieces_kept = 0;  // pieces left as they were: they would change the topology
  // Of num_pieces, those narrower than the hairline width, changed whatever the topology
  // (front_end.cpp).
  std::size_t num_hairline = 0;
  std::size_t num_components_before = 0;
  std::size_t num_components_after = 0;
  // Overlays of the whole domain with a set of pieces, to check its topology (many
  // pieces only; the costly part on large domains).
  std::size_t num_domain_checks = 0;
  bool changed = false;  // false: the domain is left exactly as it was
  // The pieces kept (num_pieces_kept of them), and where the largest one changed lies
  // (cut out, else filled in).
  struct Kept {
    Polygon piece;
    bool cut = false;  // a part of the domain narrower than the width (else a gap in it)
  };
  std::vector<Kept> kept;
  NarrowPlace largest_changed;

  // Adds a later round on the domain this one left.
  void add(const NarrowResult& later) {
    area_removed_m2 += later.area_removed_m2;
    area_added_m2 += later.area_added_m2;
    if (num_pieces == 0) largest_changed = later.largest_changed;
    num_pieces += later.num_pieces;
    num_pieces_kept = later.num_pieces_kept;
    num_hairline += later.num_hairline;
    kept = later.kept;
    num_components_after = later.num_components_after;
    num_domain_checks += later.num_domain_checks;
    changed = changed || later.changed;
  }
};

// Changes `domain` only when some feature is narrower than min_width (a piece of more
// than (min_width / 100)^2 area changes), and never its topology: a piece whose removal
// or filling would cut an isthmus, join two components, or open or close a hole (in a
// water domain, flood a land bridge or close a strait round an island) is left as it
// is. The result is oriented and sorted by area (rings are then cleaned and simplified
// by the callers as any other input). Throws Error(input) when nothing is left.
NarrowResult remove_narrow_features(Domain& domain, const NarrowParams& params);

// Gaps and strips narrower than params.min_width_m (the pieces of an opening then a
// closing at that width) that meet one of `kept` (pieces remove_narrow_features kept for
// the topology) and change the topology: closed or cut out all the same. For polygons
// that miss each other by a hair (a centimetre between two islands, a strip of a few
// millimetres between a lake and the sea), which would need elements that narrow.
// Counted in num_pieces and num_hairline.
NarrowResult close_hairlines(Domain& domain, const NarrowParams& params,
                             const std::vector<NarrowResult::Kept>& kept);

}  // namespace isoquad
