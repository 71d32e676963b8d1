// Lines read from any OGR vector source, to mark parts of the mesh boundary: the open
// (sea) boundary of an ocean model drawn as lines along the domain's edge
// (--open-boundary). Polygons count by their rings.
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

struct SourceLines {
  // Polylines in the source CRS; a ring (closed) repeats its first point at the end.
  std::vector<std::vector<Point2>> lines;
  CrsInfo crs;
  std::string layer_name;
  std::size_t num_features = 0;  // with a line or polygon geometry
};

// Reads every line, multi-line, polygon ring and curve (linearised) of the layer named
// `layer`, or else of the data set's first layer of lines, or else its first layer. In
// longitudes, each segment goes the short way round (its end moved by 360 degrees
// where needed).
// `what` names the option in messages. Throws Error(input) for a missing or unreadable
// file, a point geometry or no line at all (naming the file and feature), Error(usage)
// for no such layer, Error(crs) for a layer without a CRS. A modelling package's line
// file (model_lines.h), whose format has no CRS, takes `model_file_crs` when given.
SourceLines read_lines(const std::string& path, const std::string& layer, const std::string& what,
                       const CrsInfo* model_file_crs = nullptr);

}  // namespace isoquad
