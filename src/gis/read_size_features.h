// Vector features that ask for smaller sizes (--refine): polygons, lines and points
// from any OGR vector source, each with its size in metres in a numeric attribute; or
// polygons with a zone number each (--zones).
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

struct SizeFeature {
  double size_m = 0.0;   // or the zone's number (FeatureValue::zone)
  double width_m = 0.0;  // the size holds within width_m / 2 of the feature
  long long fid = 0;
  // In the source CRS. Rings of polygons (closed: the first point repeated), inside by
  // the even-odd rule over all of them; lines; points.
  std::vector<std::vector<Point2>> rings;
  std::vector<std::vector<Point2>> lines;
  std::vector<Point2> points;
};

struct SizeFeatures {
  std::vector<SizeFeature> features;
  CrsInfo crs;
  std::string layer_name;
};

// Reads every feature of the layer named `layer` (or the first layer) with a geometry:
// points, lines, polygons and their multi- and curved forms (linearised), each with the
// value of its attribute `field`, and of `width_field` when not empty (a width in
// metres, 0 or more). Throws Error(input) for a missing or unreadable file, a size that
// is missing or not a positive number, a width that is missing or negative, a
// coordinate that is not finite, no feature (each naming the file and feature),
// Error(usage) for no such layer or field (listing those there are), Error(crs) for a
// layer without a CRS. `what` names the option in messages.
// With FeatureValue::zone the features are polygons and the values whole numbers, 1 or
// more (Error(input) otherwise).
enum class FeatureValue { size, zone };
SizeFeatures read_size_features(const std::string& path, const std::string& layer,
                                const std::string& field, const std::string& what,
                                const std::string& width_field = "",
                                FeatureValue kind = FeatureValue::size);

}  // namespace isoquad
