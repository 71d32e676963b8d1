#include "gis/read_points.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"

namespace isoquad {

namespace {

// A CSV's points from its columns named as coordinates are (GDAL's CSV driver makes no
// geometry otherwise); other files open as they are.
std::vector<std::string> open_options(const std::string& path) {
  if (!ends_with(lower_case(path), ".csv")) return {};
  return {"X_POSSIBLE_NAMES=x,lon,long,longitude,easting,east",
          "Y_POSSIBLE_NAMES=y,lat,latitude,northing,north", "AUTODETECT_TYPE=YES"};
}

bool is_point_type(OGRwkbGeometryType type) {
  const OGRwkbGeometryType flat = wkbFlatten(type);
  return flat == wkbPoint || flat == wkbMultiPoint;
}

// The first layer of points (by its declared type, or its first geometry's when the
// type is not declared), or null.
OGRLayer* point_layer(GDALDataset& ds) {
  for (int i = 0; i < ds.GetLayerCount(); ++i) {
    OGRLayer* layer = ds.GetLayer(i);
    const OGRwkbGeometryType type = layer->GetGeomType();
    if (is_point_type(type)) return layer;
    if (wkbFlatten(type) != wkbUnknown) continue;
    layer->ResetReading();
    std::unique_ptr<OGRFeature> first(layer->GetNextFeature());
    layer->ResetReading();
    if (first && first->GetGeometryRef() &&
        is_point_type(first->GetGeometryRef()->getGeometryType()))
      return layer;
  }
  return nullptr;
}

}  // namespace

bool has_point_layer(const std::string& path) {
  try {
    GdalErrorCapture capture;
    return point_layer(*open_vector_dataset(path, "read", open_options(path))) != nullptr;
  } catch (const Error&) {
    return false;
  }
}

PointLayer read_point_layer(const std::string& path, const std::string& what, bool with_values,
                            const std::string& field, const std::string& field_option,
                            std::size_t max_points, const PointNames& names) {
  auto fail = [&](ErrorClass cls, const std::string& problem) {
    throw Error(cls, "read", what + " '" + path + "': " + problem);
  };
  GdalDataset ds = open_vector_dataset(path, what, open_options(path));
  OGRLayer* layer = point_layer(*ds);
  if (!layer)
    fail(ErrorClass::input, "holds no layer of points (layers: " + layer_names(*ds) + ")");
  PointLayer out;
  if (const OGRSpatialReference* srs = layer->GetSpatialRef()) out.crs = crs_from_srs(*srs).wkt;
  out.layer_name = layer->GetName();
  const std::string& name = out.layer_name;
  int index = -1;
  if (with_values && !field.empty()) {
    index = layer->GetLayerDefn()->GetFieldIndex(field.c_str());
    if (index < 0)
      fail(ErrorClass::usage, "layer '" + name + "' has no attribute '" + field + "' (" +
                                  field_option + "; attributes: " + field_names(*layer) + ")");
  }
  int name_index = -1;
  if (!names.field.empty()) {
    name_index = layer->GetLayerDefn()->GetFieldIndex(names.field.c_str());
    if (name_index < 0 && names.required)
      fail(ErrorClass::usage, "layer '" + name + "' has no attribute '" + names.field + "' (" +
                                  names.option + "; attributes: " + field_names(*layer) + ")");
  }
  layer->ResetReading();
  GdalErrorCapture capture;  // a CSV's "Invalid value type" warnings, said by the caller
  for (auto& feature : *layer) {
    if (out.points.size() >= max_points) break;
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || g->IsEmpty()) {
      if (out.num_without_point++ == 0) out.first_without_point = feature->GetFID();
      continue;
    }
    const std::string where = "layer '" + name + "', feature " + std::to_string(feature->GetFID());
    if (!is_point_type(g->getGeometryType()))
      fail(ErrorClass::input, where + " is a " + OGRGeometryTypeToName(g->getGeometryType()) +
                                  "; " + what + " takes points");
    double value = NAN;
    if (index >= 0) {
      if (!feature->IsFieldSetAndNotNull(index)) continue;
      const char* text = feature->GetFieldAsString(index);
      char* end = nullptr;
      value = std::strtod(text, &end);
      if (end == text || *end)
        fail(ErrorClass::input, where + " has " + field + " '" + text + "', not a number");
    } else if (with_values && !OGR_GT_HasZ(g->getGeometryType())) {
      fail(ErrorClass::usage, "layer '" + name +
                                  "' holds points without Z: name the attribute of their values "
                                  "with " +
                                  field_option + " (attributes: " + field_names(*layer) + ")");
    }
    auto add = [&](const OGRPoint& p) {
      const double v = !with_values ? 0.0 : index >= 0 ? value : p.getZ();
      if (!std::isfinite(p.getX()) || !std::isfinite(p.getY()) || !std::isfinite(v)) return;
      out.points.push_back({p.getX(), p.getY()});
      if (with_values) out.values.push_back(v);
      if (name_index >= 0)
        out.names.emplace_back(
            feature->IsFieldSetAndNotNull(name_index) ? feature->GetFieldAsString(name_index) : "");
    };
    if (wkbFlatten(g->getGeometryType()) == wkbPoint)
      add(*g->toPoint());
    else
      for (const OGRPoint* p : *g->toMultiPoint()) add(*p);
  }
  out.gdal_message = capture.last_message();
  return out;
}

}  // namespace isoquad
