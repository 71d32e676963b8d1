#include "gis/read_size_features.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "core/error.h"
#include "gis/gdal_env.h"

namespace isoquad {

namespace {

// Adds g's parts to f; false for a geometry that is none of points, lines or polygons.
bool add_geometry(const OGRGeometry& g, SizeFeature& f) {
  const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
  auto points_of = [](const OGRLineString& line) {
    std::vector<Point2> out;
    for (int i = 0; i < line.getNumPoints(); ++i) out.push_back({line.getX(i), line.getY(i)});
    return out;
  };
  if (t == wkbPoint) {
    f.points.push_back({g.toPoint()->getX(), g.toPoint()->getY()});
  } else if (t == wkbLineString) {
    std::vector<Point2> line = points_of(*g.toLineString());
    if (!line.empty()) f.lines.push_back(std::move(line));
  } else if (t == wkbPolygon) {
    for (const OGRLinearRing* ring : *g.toPolygon()) {
      std::vector<Point2> r = points_of(*ring);
      if (r.empty()) continue;
      if (r.front().x != r.back().x || r.front().y != r.back().y) r.push_back(r.front());
      f.rings.push_back(std::move(r));
    }
  } else if (OGR_GT_IsSubClassOf(t, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *g.toGeometryCollection())
      if (!add_geometry(*part, f)) return false;
  } else if (OGR_GT_IsCurve(t) || OGR_GT_IsSurface(t)) {
    std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
    return linear && wkbFlatten(linear->getGeometryType()) != t && add_geometry(*linear, f);
  } else {
    return false;
  }
  return true;
}

}  // namespace

SizeFeatures read_size_features(const std::string& path, const std::string& layer_name,
                                const std::string& field, const std::string& what,
                                const std::string& width_field, FeatureValue kind) {
  const bool zones = kind == FeatureValue::zone;
  GdalDataset ds = open_vector_dataset(path, what);
  auto fail = [&](ErrorClass cls, const std::string& why) {
    throw Error(cls, what, "'" + path + "': " + why);
  };
  OGRLayer* layer = layer_name.empty() ? ds->GetLayer(0) : ds->GetLayerByName(layer_name.c_str());
  if (!layer)
    fail(ErrorClass::usage, "no layer '" + layer_name + "' (layers: " + layer_names(*ds) + ")");
  SizeFeatures out;
  out.layer_name = layer->GetName();
  const OGRSpatialReference* srs = layer->GetSpatialRef();
  if (!srs)
    fail(ErrorClass::crs, "layer '" + out.layer_name +
                              "' has no CRS; give the file one (e.g. ogr2ogr -a_srs "
                              "EPSG:4326 with.gpkg " +
                              path + ")");
  out.crs = crs_from_srs(*srs);
  OGRFeatureDefn* defn = layer->GetLayerDefn();
  auto attribute = [&](const std::string& name, const char* purpose) {
    const int index = defn->GetFieldIndex(name.c_str());
    if (index < 0)
      fail(ErrorClass::usage, "layer '" + out.layer_name + "' has no attribute '" + name +
                                  "' for the " + purpose + " (attributes: " + field_names(*layer) +
                                  ")");
    return index;
  };
  const int index = attribute(field, zones ? "zones" : "sizes");
  const int width_index = width_field.empty() ? -1 : attribute(width_field, "widths");
  // The attribute's number; NaN when it is not set, not a number or not finite.
  auto number = [](OGRFeature& feature, int i, const char*& text) {
    char* end = nullptr;
    text = feature.GetFieldAsString(i);
    const double v = feature.IsFieldSetAndNotNull(i) ? std::strtod(text, &end) : NAN;
    return std::isfinite(v) && !(end && *end) ? v : NAN;
  };
  layer->ResetReading();
  for (auto& feature : *layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || g->IsEmpty()) continue;
    const std::string name = "feature " + std::to_string(feature->GetFID());
    SizeFeature f;
    f.fid = feature->GetFID();
    if (!add_geometry(*g, f) || (zones && (!f.lines.empty() || !f.points.empty())))
      fail(ErrorClass::input,
           name + " is a " + OGRGeometryTypeToName(g->getGeometryType()) +
               (zones ? "; zones are polygons" : "; sizes go on points, lines and polygons"));
    const char* text = nullptr;
    f.size_m = number(*feature, index, text);
    if (zones && !(f.size_m >= 1 && f.size_m == std::floor(f.size_m) && f.size_m < 1e9))
      fail(ErrorClass::input,
           name + " has " + field + " '" + text + "'; zones are whole numbers, 1 or more");
    if (!(f.size_m > 0))
      fail(ErrorClass::input,
           name + " has " + field + " '" + text + "'; sizes are positive numbers of metres");
    if (width_index >= 0) {
      f.width_m = number(*feature, width_index, text);
      if (!(f.width_m >= 0))
        fail(ErrorClass::input, name + " has " + width_field + " '" + text +
                                    "'; widths are numbers of metres, 0 or more");
    }
    for (const auto* parts : {&f.rings, &f.lines})
      for (const auto& part : *parts)
        for (const Point2& p : part)
          if (!std::isfinite(p.x) || !std::isfinite(p.y))
            fail(ErrorClass::input, name + " has a coordinate that is not finite");
    for (const Point2& p : f.points)
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        fail(ErrorClass::input, name + " has a coordinate that is not finite");
    out.features.push_back(std::move(f));
  }
  if (out.features.empty())
    fail(ErrorClass::input, "layer '" + out.layer_name + "' has no feature");
  return out;
}

}  // namespace isoquad
