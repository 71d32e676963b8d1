// Points read from any OGR vector source: soundings (SampleField), the points of
// --embed-points.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct PointLayer {
  std::vector<Point2> points;  // in the layer's CRS
  std::vector<double> values;  // with values: each point's
  std::vector<std::string> names;  // with a name attribute: each point's (its feature's)
  std::string crs;             // WKT; empty when the layer has none
  std::string layer_name;
  // Features without a point (a CSV row whose coordinates are not numbers or are empty),
  // the first's id, and what GDAL said of it.
  std::size_t num_without_point = 0;
  long long first_without_point = -1;
  std::string gdal_message;
};

// Whether `path` opens as a vector data set with a layer of points (read_point_layer).
bool has_point_layer(const std::string& path);

// The points (and multi-points) of the first layer of points in `path`: any GDAL vector
// data set, a CSV's points from its columns named x, lon, longitude, easting or east and
// y, lat, latitude, northing or north (any case). With `with_values`, each point's value:
// the attribute `field` (points where it is not set are skipped), else the point's Z.
// Points with a coordinate or value that is not finite are skipped; at most max_points
// are read. `what` names the option in messages. Throws Error(input) for a file that
// cannot be read, no layer of points, another geometry or a value that is not a number;
// Error(usage) for a missing `field`, or points without Z and no `field` (naming the
// layer's attributes and `field_option`).
// `names`: the attribute (any case) whose text names each point; a layer without it
// gives no names, unless `names_required` (then Error(usage), naming `names_option`).
struct PointNames {
  std::string field, option;
  bool required = false;
};
PointLayer read_point_layer(const std::string& path, const std::string& what, bool with_values,
                            const std::string& field = "", const std::string& field_option = "",
                            std::size_t max_points = std::numeric_limits<std::size_t>::max(),
                            const PointNames& names = PointNames());

}  // namespace isoquad
