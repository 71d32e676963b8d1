// Polygons from lines: a coastline or a domain's outline drawn as lines (a shapefile of
// lines, a land boundary exported from a modelling package) instead of polygons. Closed
// lines are rings; open lines are joined end to end into rings where exactly two line
// ends meet; the rings nest into polygons with holes by containment.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/read_polygons.h"

namespace isoquad {

// One line of one feature, in the source CRS, as read (a closed line repeats its first
// point at the end).
struct SourceLine {
  long long fid = -1;
  int part = 0;  // index within a multi-line
  std::vector<Point2> points;
};

struct LineRings {
  // rings[0] the outer ring, the rest its holes, stored open; in the order of the
  // outer rings' first lines. fid and part are those of the outer ring's first line.
  std::vector<SourcePolygon> polygons;
  std::size_t num_rings = 0;
  std::size_t num_joined_rings = 0;  // rings made of two or more open lines
  std::size_t num_lines_joined = 0;  // open lines in those rings
};

// What is wrong with the lines, naming the features and the places (no file name).
class LinesError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The rings of `lines` nested into polygons: a ring inside an even number of others
// (0, 2, ...) is an outer ring, one inside an odd number a hole of the smallest ring
// that holds it. Lines of fewer than two distinct points are ignored. Throws
// LinesError where an end of an open line meets no other end, or three or more meet.
// Rings without area, and rings that cross each other, are left to the polygons'
// checks. `units` names the coordinates' units in messages ("degrees", "m").
LineRings rings_from_lines(const std::vector<SourceLine>& lines, const std::string& units);

}  // namespace isoquad
