#include "gis/read_polygons.h"

#include <gdal.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "core/text.h"
#include "gis/gdal_env.h"
#include "gis/rings_from_lines.h"
#include "gis/where_hint.h"

namespace isoquad {

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

bool is_polygonal(OGRwkbGeometryType t) {
  const OGRwkbGeometryType f = wkbFlatten(t);
  return f == wkbPolygon || f == wkbTriangle || f == wkbMultiPolygon || f == wkbCurvePolygon ||
         f == wkbMultiSurface || f == wkbPolyhedralSurface || f == wkbTIN;
}

// Whether `g` holds an area: a polygonal geometry, or a geometry collection (as overlays
// and some GeoJSON give) with a polygonal part, at any depth.
bool has_polygonal_part(const OGRGeometry& g) {
  if (is_polygonal(g.getGeometryType())) return true;
  if (wkbFlatten(g.getGeometryType()) != wkbGeometryCollection) return false;
  for (const OGRGeometry* part : *g.toGeometryCollection())
    if (has_polygonal_part(*part)) return true;
  return false;
}

bool is_linear(OGRwkbGeometryType t) {
  const OGRwkbGeometryType f = wkbFlatten(t);
  return f == wkbLineString || f == wkbMultiLineString || f == wkbCircularString ||
         f == wkbCompoundCurve || f == wkbMultiCurve || f == wkbLinearRing;
}

// Fewer than 3 distinct points, or every point on one line: no area at all. (A ring
// whose signed area merely sums to zero, like a symmetric bow-tie, is a
// self-intersection, which the domain stage reports.)
bool is_degenerate(const Ring& ring) {
  if (ring.size() < 3) return true;
  const Point2 a = ring[0], b = ring[1];
  for (std::size_t i = 2; i < ring.size(); ++i) {
    const Point2 c = ring[i];
    if ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) != 0.0) return false;
  }
  return true;
}

class Reader {
 public:
  explicit Reader(const ReadParams& p) : p_(p) {}

  std::vector<SelectionValue> values(const std::string& field, std::string* unmatched) {
    open();
    choose_layer();
    set_crs();
    apply_bbox(true);
    apply_where();
    OGRFeatureDefn* defn = layer_->GetLayerDefn();
    const int index = defn->GetFieldIndex(field.c_str());
    // The features' ids: a GeoPackage's FID column (fid), OGR's FID elsewhere (a
    // shapefile's record numbers): a mesh per feature, such as each part of a
    // multi-polygon split by ogr2ogr -explodecollections.
    const std::string fid_column = layer_->GetFIDColumn();
    const bool by_fid =
        index < 0 && (lower_case(field) == "fid" ||
                      (!fid_column.empty() && lower_case(field) == lower_case(fid_column)));
    if (index < 0 && !by_fid)
      fail(ErrorClass::usage,
           "layer " + quote(out_.layer_name) + " has no attribute " + quote(field) +
               " (attributes: " + field_names(*layer_) +
               "; the features' ids: " + (fid_column.empty() ? "FID" : fid_column) + ")");
    const OGRFieldType type = by_fid ? OFTInteger64 : defn->GetFieldDefn(index)->GetType();
    const bool number = type == OFTInteger || type == OFTInteger64 || type == OFTReal;
    std::map<std::pair<double, std::string>, SelectionValue> sorted;
    std::string quoted = "\"";
    const std::string column = by_fid ? (fid_column.empty() ? "FID" : fid_column) : field;
    for (char c : column) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    quoted += "\"";
    if (by_fid && fid_column.empty()) quoted = "FID";  // OGR SQL's special field, unquoted
    std::string fid_ref = "FID";
    if (!fid_column.empty()) {
      fid_ref = "\"";
      for (char c : fid_column) fid_ref += c == '"' ? std::string("\"\"") : std::string(1, c);
      fid_ref += "\"";
    }
    // Each value's features by their ids, in the order read.
    std::map<std::pair<double, std::string>, std::vector<GIntBig>> ids;
    std::vector<GIntBig> null_ids;
    std::map<std::pair<double, std::string>, std::size_t> polygons;
    std::size_t null_polygons = 0;
    bool any_null = false, all_ids = true;
    layer_->ResetReading();
    for (auto& feature : *layer_) {
      const GIntBig fid = feature->GetFID();
      all_ids = all_ids && fid != OGRNullFID;
      const OGRGeometry* g = feature->GetGeometryRef();
      const OGRwkbGeometryType shape = g ? wkbFlatten(g->getGeometryType()) : wkbUnknown;
      const std::size_t parts =
          shape == wkbPolygon ? 1
          : shape == wkbMultiPolygon
              ? static_cast<std::size_t>(g->toMultiPolygon()->getNumGeometries())
              : 0;
      if (by_fid) {
        SelectionValue v{std::to_string(fid), quoted + " = " + std::to_string(fid), false, ""};
        const auto key = std::make_pair(static_cast<double>(fid), v.text);
        sorted.emplace(key, v);
        ids[key].push_back(fid);
        polygons[key] += parts;
        continue;
      }
      if (!feature->IsFieldSetAndNotNull(index)) {
        any_null = true;
        null_ids.push_back(fid);
        null_polygons += parts;
        continue;
      }
      SelectionValue v;
      v.text = feature->GetFieldAsString(index);
      // A date as ISO 8601 writes it (2020-01-31, not GDAL's 2020/01/31): for the
      // console, the table and the file names, and in the filter, which a GeoPackage's
      // SQLite compares as text.
      const OGRFieldType type = feature->GetFieldDefnRef(index)->GetType();
      if ((type == OFTDate || type == OFTDateTime) && v.text.size() >= 10 && v.text[4] == '/' &&
          v.text[7] == '/') {
        v.text[4] = v.text[7] = '-';
        // A time: 2020-01-31T10:20:30, UTC as Z (GDAL's "2020/01/31 10:20:30+00").
        if (v.text.size() > 10 && v.text[10] == ' ') v.text[10] = 'T';
        if (type == OFTDateTime && ends_with(v.text, "+00"))
          v.text.replace(v.text.size() - 3, 3, "Z");
      }
      if (number) {
        v.filter = quoted + " = " + v.text;
      } else {
        v.filter = quoted + " = '";
        for (char c : v.text) v.filter += c == '\'' ? std::string("''") : std::string(1, c);
        v.filter += "'";
      }
      const auto key = std::make_pair(number ? feature->GetFieldAsDouble(index) : 0.0, v.text);
      sorted.emplace(key, v);
      ids[key].push_back(fid);
      polygons[key] += parts;
    }
    auto id_filter = [&](const std::vector<GIntBig>& fids, const std::string& fallback) {
      if (!all_ids) return fallback;
      std::string f = fid_ref + " IN (";
      for (std::size_t i = 0; i < fids.size(); ++i) f += (i ? "," : "") + std::to_string(fids[i]);
      return f + ")";
    };
    std::vector<SelectionValue> out;
    for (auto& [key, v] : sorted) {
      v.id_filter = id_filter(ids[key], v.filter);
      v.num_features = ids[key].size();
      v.num_polygons = polygons[key];
      out.push_back(std::move(v));
    }
    if (any_null) {
      SelectionValue v{"", quoted + " IS NULL", true, ""};
      v.id_filter = id_filter(null_ids, v.filter);
      v.num_features = null_ids.size();
      v.num_polygons = null_polygons;
      out.push_back(std::move(v));
    }
    if (unmatched && !out.empty()) *unmatched = unmatched_values();
    // A --where that matches nothing: said as reading it says it (the nearest values).
    if (out.empty() && !p_.where.empty()) fail_matched_nothing();
    return out;
  }

  SourceData run() {
    open();
    choose_layer();
    set_crs();
    apply_bbox(false);
    apply_where();
    read_features();
    check_coordinate_range();
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(ErrorClass cls, const std::string& what) const {
    throw Error(cls, "read", quote(p_.path) + ": " + what);
  }

  // The selection's options for messages: " --where '...' --bbox --clip", or empty.
  std::string selection_words() const {
    std::string selection;
    if (!p_.where.empty()) selection += " --where " + quote(p_.where);
    if (p_.bbox) selection += " --bbox";
    if (p_.clip) selection += " --clip";
    return selection;
  }

  // The selection took no feature of the layer: with --where, the values it compares
  // that the layer lacks, and their nearest.
  [[noreturn]] void fail_matched_nothing() const {
    const std::string hint =
        p_.where.empty()
            ? ""
            : where_hint(*layer_, p_.where, p_.clip ? "the area of --clip" : "the bbox");
    fail(ErrorClass::input, "the selection (" + selection_words().substr(1) +
                                ") matched no feature in layer " + quote(out_.layer_name) +
                                (hint.empty() ? "" : ": " + hint));
  }

  void open() { ds_ = open_vector_dataset(p_.path, "read"); }

  void choose_layer() {
    if (!p_.layer.empty()) {
      layer_ = ds_->GetLayerByName(p_.layer.c_str());
      if (!layer_) {
        fail(ErrorClass::usage,
             "no layer " + quote(p_.layer) + " (layers: " + layer_names(*ds_) + ")");
      }
    } else if (ds_->GetLayerCount() == 1) {
      layer_ = ds_->GetLayer(0);
    } else {
      // The first layer of polygons; the others are named in the summary.
      for (int i = 0; i < ds_->GetLayerCount(); ++i) {
        OGRLayer* layer = ds_->GetLayer(i);
        if (!holds_polygons(*layer)) continue;
        if (!layer_)
          layer_ = layer;
        else
          out_.other_polygon_layers.push_back(layer->GetName());
      }
      if (!layer_) layer_ = ds_->GetLayer(0);
    }
    out_.layer_name = layer_->GetName();
  }

  // Whether `layer` is one of polygons: by its declared type, or by its first geometry
  // where it declares none (a TopoJSON's objects, a GeoJSON of mixed types).
  static bool holds_polygons(OGRLayer& layer) {
    const OGRwkbGeometryType type = layer.GetGeomType();
    if (wkbFlatten(type) != wkbUnknown) return is_polygonal(type);
    layer.ResetReading();
    for (auto& feature : layer)
      if (const OGRGeometry* g = feature->GetGeometryRef()) {
        layer.ResetReading();
        return has_polygonal_part(*g);
      }
    layer.ResetReading();
    return false;
  }

  void set_crs() {
    if (!p_.src_crs.empty()) {
      out_.crs = parse_crs(p_.src_crs, "--src-crs");
    } else {
      const std::string declared = declared_crs_problem(*ds_, *layer_);
      if (!declared.empty())
        fail(ErrorClass::crs, declared + "; give the CRS of the coordinates with --src-crs");
      const OGRSpatialReference* srs = layer_->GetSpatialRef();
      if (!srs && !p_.default_crs.empty()) {
        out_.crs = parse_crs(p_.default_crs, "the CRS of " + quote(out_.layer_name));
        return;
      }
      if (!srs) {
        // Coordinates in degrees' range are most likely longitudes and latitudes (a
        // TopoJSON file's, world-atlas's): say so.
        OGREnvelope e;
        const bool degrees = layer_->GetExtent(&e, TRUE) == OGRERR_NONE && e.MinX >= -180.0 &&
                             e.MaxX <= 360.0 && e.MinY >= -90.0 && e.MaxY <= 90.0;
        fail(ErrorClass::crs,
             "layer " + quote(out_.layer_name) +
                 " has no CRS; give the CRS of the coordinates with --src-crs" +
                 (degrees ? std::string(" (they lie within longitudes' and latitudes' range: "
                                        "--src-crs EPSG:4326 if that is what they are, as a "
                                        "TopoJSON file's usually are)")
                          : std::string()));
      }
      out_.crs = crs_from_srs(*srs);
    }
  }

  // The values --where compares a text attribute with that no feature read holds, while
  // others match ("name IN ('France', 'Frnace')"): what to say, or empty.
  std::string unmatched_values() {
    if (p_.where.empty()) return "";
    const std::string hint =
        where_hint(*layer_, p_.where, p_.clip ? "the area of --clip" : "the bbox");
    return hint.empty() ? "" : "--where " + quote(p_.where) + ": " + hint;
  }

  // A --bbox in a projected CRS whose numbers look like degrees: what to say.
  std::string degrees_hint() const {
    if (!p_.bbox) return "";
    const CrsInfo crs = p_.bbox_crs.empty() ? out_.crs : parse_crs(p_.bbox_crs, "--bbox-crs");
    const auto& b = *p_.bbox;
    if (crs.geographic || std::abs(b[0]) > 360 || std::abs(b[2]) > 360 || std::abs(b[1]) > 90 ||
        std::abs(b[3]) > 90)
      return "";
    return "; its numbers look like longitudes and latitudes, and " + quote(crs.name) +
           " is projected: --bbox-crs EPSG:4326?";
  }

  // `filter_lines`: a layer of lines is filtered too (the values of --each: those of the
  // lines that reach the bbox); otherwise it is read whole (polygons_from_lines).
  void apply_bbox(bool filter_lines) {
    if (!p_.bbox && !p_.clip) return;
    std::string what;
    Ring ring = selection_area(p_, out_.crs, what);
    double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
    for (const Point2& q : ring)
      xmin = std::min(xmin, q.x), xmax = std::max(xmax, q.x), ymin = std::min(ymin, q.y),
      ymax = std::max(ymax, q.y);
    // In longitudes, a bbox across the antimeridian (176 to 182) also reads what the data
    // draws 360 degrees away (-180 to -178).
    std::vector<double> shifts{0.0};
    if (out_.crs.geographic && xmax > 180.0) shifts.push_back(-360.0);
    if (out_.crs.geographic && xmin < -180.0) shifts.push_back(360.0);
    OGRMultiPolygon area;
    for (double dx : shifts) {
      OGREnvelope e;
      e.MinX = xmin + dx, e.MinY = ymin, e.MaxX = xmax + dx, e.MaxY = ymax;
      filters_.push_back(e);
      OGRLinearRing r;
      r.addPoint(e.MinX, e.MinY), r.addPoint(e.MaxX, e.MinY), r.addPoint(e.MaxX, e.MaxY);
      r.addPoint(e.MinX, e.MaxY), r.addPoint(e.MinX, e.MinY);
      OGRPolygon poly;
      poly.addRing(&r);
      area.addGeometry(&poly);
    }
    OGREnvelope ext;
    if (layer_->GetExtent(&ext, TRUE) == OGRERR_NONE) {
      reach_pole(ext);
      if (!p_.empty_area_ok &&
          std::none_of(filters_.begin(), filters_.end(),
                       [&](const OGREnvelope& f) { return f.Intersects(ext); }))
        fail(ErrorClass::input, what + " misses the data of layer " + quote(out_.layer_name) +
                                    " (extent " + fmt(ext.MinX) + "," + fmt(ext.MinY) + "," +
                                    fmt(ext.MaxX) + "," + fmt(ext.MaxY) + " in " + out_.crs.name +
                                    ")" + degrees_hint());
    }
    // OGR's filter tests the geometry itself, drawn in lon/lat: land round a pole that
    // it does not reach as drawn (reach_pole) would miss a bbox near the pole. Polar
    // bboxes read every feature; add_polygon selects the parts.
    const bool polar = out_.crs.geographic && (ymax <= -60.0 || ymin >= 60.0);
    if (!filter_lines && is_linear(layer_->GetGeomType())) {
      out_.bbox_ring = std::move(ring);
      return;
    }
    if (!polar && filters_.size() == 1) layer_->SetSpatialFilterRect(xmin, ymin, xmax, ymax);
    if (!polar && filters_.size() > 1) layer_->SetSpatialFilter(&area);
    out_.bbox_ring = std::move(ring);
  }

  void apply_where() {
    if (p_.where.empty()) return;
    GdalErrorCapture capture;
    if (layer_->SetAttributeFilter(p_.where.c_str()) != OGRERR_NONE)
      fail(ErrorClass::usage, "--where " + quote(p_.where) + " is not a valid filter on layer " +
                                  quote(out_.layer_name) + ": " + capture.last_message() +
                                  filter_help(*layer_, p_.where, capture.last_message()));
  }

  void read_features() {
    layer_->ResetReading();
    std::size_t num_other = 0, num_empty = 0;
    GdalErrorCapture capture;
    std::vector<SourceLine> lines;
    std::size_t num_polygonal = 0;
    for (auto& feature : *layer_) {
      ++out_.num_features;
      const OGRGeometry* g = feature->GetGeometryRef();
      if (!g || g->IsEmpty() || !has_polygonal_part(*g)) {
        ++out_.num_features_skipped;
        if (g && !g->IsEmpty()) ++num_other;
        else ++num_empty;
        if (g && !g->IsEmpty() && is_linear(g->getGeometryType())) ++out_.num_line_features;
        if (g && num_polygonal == 0) add_lines(feature->GetFID(), *g, lines);
        continue;
      }
      ++num_polygonal;
      std::unique_ptr<OGRGeometry> linear(g->getLinearGeometry());
      part_count_ = 0;
      add_geometry(feature->GetFID(), *linear);
    }
    if (!capture.last_message().empty() && out_.num_features == 0)
      fail(ErrorClass::input, "reading layer " + quote(out_.layer_name) + " failed: " +
                                  capture.last_message());
    if (num_polygonal == 0 && out_.num_line_features > 0) {
      num_other -= out_.num_line_features;  // before a second reading counts them again
      polygons_from_lines(std::move(lines));
    }
    const std::string selection = selection_words();
    if (out_.polygons.empty() && p_.empty_bbox_selection_ok && (p_.bbox || p_.clip) &&
        p_.where.empty() && (out_.num_features == 0 || num_other == 0)) {
      const char* area = p_.clip ? "area of --clip" : "bbox";
      out_.warnings.push_back("no polygon of layer " + quote(out_.layer_name) + " reaches the " +
                              area + ": the water domain is the whole " + area);
      return;
    }
    if (num_parts_ignored_ > 0)
      out_.warnings.push_back(std::to_string(num_parts_ignored_) +
                              " point or line part(s) of geometry collections ignored (the "
                              "first in feature " +
                              std::to_string(first_feature_ignored_) +
                              "); their polygons are read");
    // Whole features of points or lines beside the polygons (a closed line would make a
    // ring in a layer of lines): ignored, and said.
    if (!out_.polygons.empty() && num_other > 0)
      out_.warnings.push_back(std::to_string(num_other) + " feature(s) of points or lines in " +
                              "layer " + quote(out_.layer_name) +
                              " ignored; only its polygons are read");
    if (out_.polygons.empty() && out_.num_rings_from_lines > 0 && !selection.empty())
      fail(ErrorClass::input, "the " + std::to_string(out_.num_rings_from_lines) +
                                  " ring(s) the lines of layer " + quote(out_.layer_name) +
                                  " make all miss the selection (" + selection.substr(1) + ")");
    if (out_.num_features == 0) {
      if (selection.empty()) fail(ErrorClass::input, "layer " + quote(out_.layer_name) + " is empty");
      if (p_.empty_area_ok && (p_.bbox || p_.clip) && where_matches_elsewhere()) return;
      fail_matched_nothing();
    }
    if (p_.hint_unmatched_values) {
      const std::string unmatched = unmatched_values();
      if (!unmatched.empty()) out_.warnings.push_back(unmatched);
    }
    // Polygons whose boxes reach the area but none of whose parts do.
    if (out_.polygons.empty() && p_.empty_area_ok && (p_.bbox || p_.clip) && num_other == 0) return;
    if (out_.polygons.empty())
      fail(ErrorClass::input, "layer " + quote(out_.layer_name) + " has no polygons (" +
                                  std::to_string(out_.num_features) + " feature(s) read, " +
                                  std::to_string(num_other) + " with point or line geometry, " +
                                  std::to_string(num_empty) + " with none or an empty one" +
                                  (selection.empty() ? "" : ", after" + selection) + ")");
  }

  // Whether --where (or no --where) selects features of the layer outside the area read.
  bool where_matches_elsewhere() {
    layer_->SetSpatialFilter(nullptr);
    return layer_->GetFeatureCount() > 0;
  }

  void add_geometry(long long fid, const OGRGeometry& g) {
    const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
    if (t == wkbPolygon || t == wkbTriangle) {  // a triangle is a polygon of one ring
      add_polygon(fid, static_cast<int>(part_count_++), *g.toPolygon());
    } else if (!g.IsEmpty() && t != wkbMultiPolygon && t != wkbPolyhedralSurface && t != wkbTIN &&
               t != wkbGeometryCollection) {
      if (num_parts_ignored_++ == 0) first_feature_ignored_ = fid;  // a point or line
    } else if (t == wkbMultiPolygon || t == wkbPolyhedralSurface || t == wkbTIN ||
               t == wkbGeometryCollection) {
      const auto* coll = dynamic_cast<const OGRGeometryCollection*>(&g);
      if (coll) {
        for (const OGRGeometry* part : *coll) add_geometry(fid, *part);
      } else if (t == wkbPolyhedralSurface || t == wkbTIN) {
        std::unique_ptr<OGRGeometry> mp(OGRGeometryFactory::forceToMultiPolygon(g.clone()));
        add_geometry(fid, *mp);
      }
    }
  }

  // In longitudes, what spans every longitude may be drawn round a pole without
  // reaching it (world-atlas's Antarctica stops at 85 S, the pole implied): its envelope
  // reaches the pole.
  void reach_pole(OGREnvelope& e) const {
    if (!out_.crs.geographic || e.MaxX - e.MinX < 359.0) return;
    if (e.MaxY < 0.0) e.MinY = -90.0;
    if (e.MinY > 0.0) e.MaxY = 90.0;
  }

  static std::string ring_name(long long fid, int part, int ring_index) {
    return "feature " + std::to_string(fid) +
           (part ? " part " + std::to_string(part) : std::string()) + " ring " +
           std::to_string(ring_index);
  }

  // The points of a line or ring, checked to be finite.
  std::vector<Point2> finite_points(const OGRSimpleCurve& curve, const std::string& where) const {
    std::vector<Point2> points;
    points.reserve(curve.getNumPoints());
    for (int i = 0; i < curve.getNumPoints(); ++i) {
      const double x = curve.getX(i), y = curve.getY(i);
      if (!std::isfinite(x) || !std::isfinite(y))
        fail(ErrorClass::input, where + " vertex " + std::to_string(i) +
                                    ": coordinate is not finite (" + fmt(x) + ", " + fmt(y) + ")");
      points.push_back({x, y});
    }
    return points;
  }

  void add_lines(long long fid, const OGRGeometry& g, std::vector<SourceLine>& lines) const {
    if (!is_linear(g.getGeometryType()) || g.IsEmpty()) return;
    std::unique_ptr<OGRGeometry> linear(g.getLinearGeometry());
    std::vector<const OGRLineString*> parts;
    if (const auto* coll = dynamic_cast<const OGRGeometryCollection*>(linear.get())) {
      for (const OGRGeometry* part : *coll)
        if (const auto* ls = dynamic_cast<const OGRLineString*>(part)) parts.push_back(ls);
    } else if (const auto* ls = dynamic_cast<const OGRLineString*>(linear.get())) {
      parts.push_back(ls);
    }
    for (std::size_t k = 0; k < parts.size(); ++k) {
      SourceLine line;
      line.fid = fid;
      line.part = static_cast<int>(k);
      line.points =
          finite_points(*parts[k], "feature " + std::to_string(fid) +
                                       (k ? " part " + std::to_string(k) : std::string()));
      lines.push_back(std::move(line));
    }
  }

  // A layer of lines without polygons: the lines' rings, nested, are the polygons. The
  // bbox selects the polygons, not the lines: a ring drawn as several lines is read
  // whole where only some of them reach the bbox.
  void polygons_from_lines(std::vector<SourceLine> lines) {
    if (layer_->GetSpatialFilter()) {
      layer_->SetSpatialFilter(nullptr);
      layer_->ResetReading();
      lines.clear();
      out_.num_line_features = 0;
      for (auto& feature : *layer_) {
        const OGRGeometry* g = feature->GetGeometryRef();
        if (!g || g->IsEmpty() || !is_linear(g->getGeometryType())) continue;
        ++out_.num_line_features;
        add_lines(feature->GetFID(), *g, lines);
      }
    }
    LineRings built;
    try {
      built = rings_from_lines(lines, out_.crs.geographic ? "degrees" : "CRS units");
    } catch (const LinesError& e) {
      fail(ErrorClass::input,
           "layer " + quote(out_.layer_name) +
               " has no polygons, and its lines do not close into rings: " + e.what());
    }
    out_.num_rings_from_lines = built.num_rings;
    out_.num_rings_joined = built.num_joined_rings;
    out_.num_lines_joined = built.num_lines_joined;
    for (SourcePolygon& sp : built.polygons) {
      const std::array<double, 4> b = bounding_box(sp.rings[0]);
      OGREnvelope envelope;
      envelope.MinX = b[0], envelope.MinY = b[1], envelope.MaxX = b[2], envelope.MaxY = b[3];
      if (!misses_bbox(envelope)) add_rings(sp.fid, sp.part, std::move(sp.rings));
    }
  }

  // The bbox filter selects whole features; a part of a multipolygon (the land of the
  // world as one feature) that misses the bbox is not read, nor checked.
  bool misses_bbox(OGREnvelope e) const {
    if (filters_.empty()) return false;
    reach_pole(e);
    return std::none_of(filters_.begin(), filters_.end(),
                        [&](const OGREnvelope& f) { return e.Intersects(f); });
  }

  void add_polygon(long long fid, int part, const OGRPolygon& poly) {
    OGREnvelope envelope;
    poly.getEnvelope(&envelope);
    if (misses_bbox(envelope)) return;
    std::vector<Ring> rings;
    int ring_index = 0;
    for (const OGRLinearRing* r : poly) {
      const std::string where = ring_name(fid, part, ring_index++);
      Ring ring = finite_points(*r, where);
      const bool closed = ring.size() >= 2 && ring.front() == ring.back();
      if (!closed && !ring.empty()) {
        if (!p_.repair)
          fail(ErrorClass::input,
               where + " is not closed: first point (" + fmt(ring.front().x) + ", " +
                   fmt(ring.front().y) + ") differs from last point (" + fmt(ring.back().x) +
                   ", " + fmt(ring.back().y) + "); use --repair to close it");
        ++out_.num_rings_closed;
      }
      if (closed) ring.pop_back();
      rings.push_back(std::move(ring));
    }
    add_rings(fid, part, std::move(rings));
  }

  // A polygon's rings, stored open: rings[0] the outer one.
  void add_rings(long long fid, int part, std::vector<Ring> rings) {
    SourcePolygon sp;
    sp.fid = fid;
    sp.part = part;
    int ring_index = 0;
    for (Ring& ring : rings) {
      const std::string where = ring_name(fid, part, ring_index);
      out_.num_points_removed += remove_duplicates_and_spikes(ring);
      if (is_degenerate(ring)) {
        // A ring along one parallel round (most of) the globe ("north of 66.5 N" drawn as the
        // Arctic Circle): a line in longitude and latitude, which no repair can read as
        // the cap the user means.
        if (out_.crs.geographic && rings.size() == 1 && ring.size() >= 3) {
          double x0 = ring[0].x, x1 = ring[0].x, y0 = ring[0].y, y1 = ring[0].y;
          for (const Point2& q : ring)
            x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y),
            y1 = std::max(y1, q.y);
          if (x1 - x0 >= 300.0 && y1 - y0 <= 1e-9 && std::abs(y0) < 90.0) {
            const std::string lat = fmt(std::abs(y0)) + (y0 >= 0 ? " N" : " S");
            const std::string pole = y0 >= 0 ? "90" : "-90";
            fail(ErrorClass::input,
                 where + " runs along the parallel " + lat +
                     " round every longitude: in longitude and latitude that is a line, "
                     "enclosing nothing; for the cap beyond it, close the ring through the "
                     "pole (after its last point, add (180, " +
                     fmt(y0) + "), (180, " + pole + ") and (-180, " + pole +
                     ")), or give --bbox=-180," +
                     (y0 >= 0 ? fmt(y0) + ",180,90" : "-90,180," + fmt(y0)) +
                     " with --domain water over a land layer");
          }
        }
        if (!p_.repair)
          fail(ErrorClass::input, where + " is degenerate (fewer than 3 distinct points, or all "
                                          "on one line); use --repair to drop it");
        ++out_.num_rings_dropped;
        if (ring_index == 0) {
          // Without its outer ring each hole is a polygon of its own. A spherical polygon
          // drawn round a pole is so (world-atlas's Antarctica at 1:50m: a ring along
          // 89.999 S, with the coast as its hole); the coast is the land.
          if (rings.size() > 1)
            out_.warnings.push_back(where + " has no area; its " +
                                    std::to_string(rings.size() - 1) +
                                    " hole(s) are read as polygons of their own");
          for (std::size_t k = 1; k < rings.size(); ++k)
            add_rings(fid, part, {std::move(rings[k])});
          return;
        }
      } else {
        sp.rings.push_back(std::move(ring));
      }
      ++ring_index;
    }
    if (!sp.rings.empty()) out_.polygons.push_back(std::move(sp));
  }

  void check_coordinate_range() {
    // Geographic coordinates: longitude and latitude must be possible.
    if (out_.crs.geographic) {
      for (const SourcePolygon& sp : out_.polygons)
        for (const Ring& r : sp.rings)
          for (const Point2& q : r)
            if (std::abs(q.y) > 90.0 || q.x < -360.0 || q.x > 360.0)
              fail(ErrorClass::crs, "feature " + std::to_string(sp.fid) + ": coordinate (" +
                                        fmt(q.x) + ", " + fmt(q.y) +
                                        ") is outside the valid range of " + quote(out_.crs.name) +
                                        " (longitude -360..360, latitude -90..90); are the "
                                        "coordinates in another CRS? Use --src-crs");
      return;
    }
    // Projected: every point must map back to longitude and latitude, and the data must
    // lie near the CRS's area of use.
    CrsInfo geog = geographic_base(out_.crs);
    CrsTransform to_geog(out_.crs, geog);
    double aou[4];
    const bool has_aou = crs_area_of_use(out_.crs, aou);
    for (const SourcePolygon& sp : out_.polygons)
      for (const Ring& r : sp.rings) {
        Ring copy = r;
        const long bad = to_geog.transform(copy);
        if (bad >= 0)
          fail(ErrorClass::crs, "feature " + std::to_string(sp.fid) + ": coordinate (" +
                                    fmt(r[bad].x) + ", " + fmt(r[bad].y) +
                                    ") is outside the valid range of " + quote(out_.crs.name));
        if (!has_aou) continue;
        const double margin = 10.0;  // degrees: data near a CRS's area is common and fine
        for (std::size_t i = 0; i < copy.size(); ++i) {
          const Point2& q = copy[i];
          if (q.x < aou[0] - margin || q.x > aou[2] + margin || q.y < aou[1] - margin ||
              q.y > aou[3] + margin)
            fail(ErrorClass::crs, "feature " + std::to_string(sp.fid) + ": coordinate (" +
                                      fmt(r[i].x) + ", " + fmt(r[i].y) + ") lies at lon " +
                                      fmt(q.x) + ", lat " + fmt(q.y) +
                                      ", far outside the area of use of " + quote(out_.crs.name) +
                                      "; are the coordinates in another CRS? Use --src-crs");
        }
      }
  }

  const ReadParams& p_;
  std::vector<OGREnvelope> filters_;  // the bbox's extent in the source CRS (and wrapped)
  GdalDataset ds_;
  OGRLayer* layer_ = nullptr;
  std::size_t part_count_ = 0;
  std::size_t num_parts_ignored_ = 0;  // points and lines in geometry collections
  long long first_feature_ignored_ = -1;
  SourceData out_;
};

}  // namespace

Ring selection_area(const ReadParams& p, const CrsInfo& crs, std::string& what) {
  Ring ring;
  what = p.clip_name;
  if (p.clip) {
    ring = *p.clip;
  } else {
    const auto& b = *p.bbox;
    for (double v : b)
      if (!std::isfinite(v))
        throw Error(ErrorClass::usage, "read",
                    quote(p.path) + ": --bbox has a value that is not finite");
    if (!(b[0] < b[2] && b[1] < b[3]))
      throw Error(
          ErrorClass::usage, "read",
          quote(p.path) + ": --bbox must be XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX");
    ring = densified_box(b, 64);
    what = "--bbox " + fmt(b[0]) + "," + fmt(b[1]) + "," + fmt(b[2]) + "," + fmt(b[3]);
  }
  if (!p.bbox_crs.empty()) {
    const CrsInfo from = parse_crs(p.bbox_crs, "--bbox-crs");
    if (CrsTransform(from, crs).transform(ring) >= 0)
      throw Error(ErrorClass::crs, "read",
                  quote(p.path) + ": " + (p.clip ? what : std::string("--bbox")) +
                      " cannot be transformed from " + quote(from.name) + " to " + quote(crs.name));
  }
  return ring;
}

Ring densified_box(const std::array<double, 4>& b, int per_side) {
  Ring ring;
  const Point2 corners[4] = {{b[0], b[1]}, {b[2], b[1]}, {b[2], b[3]}, {b[0], b[3]}};
  for (int s = 0; s < 4; ++s) {
    const Point2 a = corners[s], c = corners[(s + 1) % 4];
    for (int i = 0; i < per_side; ++i) {
      const double t = static_cast<double>(i) / per_side;
      ring.push_back({a.x + t * (c.x - a.x), a.y + t * (c.y - a.y)});
    }
  }
  return ring;
}

SourceData read_polygons(const ReadParams& params) { return Reader(params).run(); }

std::vector<SelectionValue> selection_values(const ReadParams& params, const std::string& field,
                                             std::string* unmatched) {
  return Reader(params).values(field, unmatched);
}

Error read_error_of_option(const Error& e, const std::string& option) {
  std::string message = e.message();
  const std::string where = option + "-where";
  for (std::size_t at = message.find("--where"); at != std::string::npos;
       at = message.find("--where", at + where.size()))
    message.replace(at, 7, where);
  return Error(e.error_class(), e.stage(), option + ": " + message);
}

Ring read_clip_area(const std::string& path, const std::string& layer, const std::string& where,
                    std::string& crs_wkt) {
  ReadParams params;
  params.path = path;
  params.layer = layer;
  params.where = where;
  SourceData area;
  try {
    area = read_polygons(params);
  } catch (const Error& e) {
    throw read_error_of_option(e, "--clip");
  }
  const std::string file = "--clip '" + path + "'";
  if (area.polygons.size() != 1)
    throw Error(ErrorClass::input, "read",
                file + (where.empty() ? "" : " --clip-where " + quote(where)) + " holds " +
                    std::to_string(area.polygons.size()) +
                    " polygons: it takes one, the area to mesh (merge them first, pick one "
                    "with --clip-where, or mesh each with --each-clip FIELD; a multi-polygon's "
                    "parts split into features first, as ogr2ogr -explodecollections does)");
  const std::vector<Ring>& rings = area.polygons.front().rings;
  if (rings.size() != 1)
    throw Error(ErrorClass::input, "read",
                file + ": its polygon has " + std::to_string(rings.size() - 1) +
                    " hole(s): the area to mesh is one ring");
  const Ring& ring = rings.front();
  {
    OGRLinearRing lr;
    for (const Point2& p : ring) lr.addPoint(p.x, p.y);
    lr.closeRings();
    OGRPolygon polygon;
    polygon.addRing(&lr);
    GdalErrorCapture capture;  // GEOS's reason, for the message
    if (!polygon.IsValid()) {
      const std::string reason = capture.last_message();
      throw Error(ErrorClass::input, "read",
                  file + ": its polygon is invalid" + (reason.empty() ? "" : " (" + reason + ")") +
                      ": draw it again, or fix it (QGIS: Fix geometries)");
    }
  }
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Point2& p : ring)
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  const double piece = std::max(x1 - x0, y1 - y0) / 64.0;
  Ring dense;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    const int n = std::max(1, static_cast<int>(std::ceil(distance(a, b) / piece)));
    for (int k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / n;
      dense.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  crs_wkt = area.crs.wkt;
  return dense;
}

}  // namespace isoquad
