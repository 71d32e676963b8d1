#include "gis/read_lines.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <memory>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "gis/model_lines.h"

namespace isoquad {

namespace {

void add_lines(const OGRGeometry& g, std::vector<std::vector<Point2>>& out, bool& other) {
  const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
  if (t == wkbLineString || t == wkbLinearRing) {
    const OGRLineString& line = *g.toLineString();
    std::vector<Point2> points;
    for (int i = 0; i < line.getNumPoints(); ++i) {
      const Point2 p{line.getX(i), line.getY(i)};
      if (points.empty() || p.x != points.back().x || p.y != points.back().y) points.push_back(p);
    }
    if (points.size() >= 2) out.push_back(std::move(points));
  } else if (t == wkbPolygon) {
    for (const OGRLinearRing* ring : *g.toPolygon()) add_lines(*ring, out, other);
  } else if (OGR_GT_IsSubClassOf(t, wkbGeometryCollection) ||
             OGR_GT_IsSubClassOf(t, wkbPolyhedralSurface)) {
    std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
    const auto* coll = dynamic_cast<const OGRGeometryCollection*>(linear.get());
    if (coll) {
      for (const OGRGeometry* part : *coll) add_lines(*part, out, other);
    } else if (linear && wkbFlatten(linear->getGeometryType()) != t) {
      add_lines(*linear, out, other);
    } else {
      other = true;
    }
  } else if (OGR_GT_IsCurve(t) || OGR_GT_IsSurface(t)) {
    std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
    if (linear) add_lines(*linear, out, other);
  } else {
    other = true;
  }
}

}  // namespace

SourceLines read_lines(const std::string& path, const std::string& layer_name,
                       const std::string& what, const CrsInfo* model_file_crs) {
  GdalDataset ds = open_vector_dataset(path, what);
  auto fail = [&](ErrorClass cls, const std::string& why) {
    throw Error(cls, what, "'" + path + "': " + why);
  };
  OGRLayer* layer = nullptr;
  if (!layer_name.empty()) {
    layer = ds->GetLayerByName(layer_name.c_str());
    if (!layer)
      fail(ErrorClass::usage, "no layer '" + layer_name + "' (layers: " + layer_names(*ds) + ")");
  } else {
    // The first layer of lines (a project's GeoPackage may hold the domain's polygons
    // first), else the first layer.
    for (int i = 0; i < ds->GetLayerCount() && !layer; ++i)
      if (OGR_GT_IsCurve(wkbFlatten(ds->GetLayer(i)->GetGeomType())) ||
          OGR_GT_IsSubClassOf(wkbFlatten(ds->GetLayer(i)->GetGeomType()), wkbMultiCurve))
        layer = ds->GetLayer(i);
    if (!layer) layer = ds->GetLayer(0);
  }
  SourceLines out;
  out.layer_name = layer->GetName();
  const OGRSpatialReference* srs = layer->GetSpatialRef();
  if (srs)
    out.crs = crs_from_srs(*srs);
  else if (model_file_crs && is_model_lines_file(path))
    out.crs = *model_file_crs;
  else
    fail(ErrorClass::crs, "layer '" + out.layer_name +
                              "' has no CRS; give the file one (e.g. ogr2ogr -a_srs "
                              "EPSG:4326 with.gpkg " +
                              path + ")");
  layer->ResetReading();
  for (auto& feature : *layer) {
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g || g->IsEmpty()) continue;
    bool other = false;
    const std::size_t before = out.lines.size();
    add_lines(*g, out.lines, other);
    if (other)
      fail(ErrorClass::input, "feature " + std::to_string(feature->GetFID()) + " is a " +
                                  OGRGeometryTypeToName(g->getGeometryType()) +
                                  "; only lines and polygons mark the boundary");
    for (std::size_t k = before; k < out.lines.size(); ++k)
      for (const Point2& p : out.lines[k])
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
          fail(ErrorClass::input, "feature " + std::to_string(feature->GetFID()) +
                                      " has a coordinate that is not finite");
    if (out.lines.size() > before) ++out.num_features;
  }
  if (out.lines.empty())
    fail(ErrorClass::input, "layer '" + out.layer_name + "' has no line or polygon");
  // In longitudes, a segment goes the short way round: one drawn across the
  // antimeridian (179.5 to -179.5) ends at 180.5, as a domain across it is read.
  if (out.crs.geographic)
    for (auto& line : out.lines)
      for (std::size_t i = 1; i < line.size(); ++i)
        line[i].x += 360.0 * std::round((line[i - 1].x - line[i].x) / 360.0);
  return out;
}

}  // namespace isoquad
