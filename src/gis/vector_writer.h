// A vector file written atomically, layer by layer: the common part of every GeoPackage
// output (domain, fields, mesh), and of the mesh's quads as GeoJSON or FlatGeobuf.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"

class GDALDataset;
class OGRLayer;
class OGRGeometry;

namespace isoquad {

// boolean: 0 or 1 in FieldValue::i, stored as an integer of GDAL's boolean subtype (a
// GeoPackage BOOLEAN column, a check box in QGIS).
enum class FieldType { integer, boolean, real, text };

struct FieldDef {
  std::string name;
  FieldType type = FieldType::real;
};

// One attribute value; the variant follows the field's type.
struct FieldValue {
  long long i = 0;
  double r = 0.0;
  std::string s;
  bool null = false;  // no value (NULL), whatever the field's type
  static FieldValue none() {
    FieldValue f;
    f.null = true;
    return f;
  }
  static FieldValue integer(long long v) {
    FieldValue f;
    f.i = v;
    return f;
  }
  static FieldValue boolean(bool v) { return integer(v ? 1 : 0); }
  static FieldValue real(double v) {
    FieldValue f;
    f.r = v;
    return f;
  }
  static FieldValue text(std::string v) {
    FieldValue f;
    f.s = std::move(v);
    return f;
  }
};

enum class GeometryKind { point, line, polygon, none };  // none: an attribute table

// What QGIS shows as a layer's title and abstract (Layer Properties, Information): a
// GeoPackage's gpkg_contents identifier (unique in the file) and description. The other
// formats have no place for them.
struct LayerAbout {
  std::string title, description;
};

class VectorWriter {
 public:
  // Creates the temporary file next to `path` with OGR's driver (GeoPackage by default;
  // "GeoJSON" or "FlatGeobuf" hold one layer), its layers created with `layer_options`
  // (OGR's NAME=VALUE). Throws Error(output), naming `shown_path` when given (the final
  // name, when `path` is an OutputSet's temporary file), else `path`.
  VectorWriter(const std::string& path, bool overwrite, const std::string& crs_wkt,
               const std::string& driver = "GPKG",
               const std::vector<std::string>& layer_options = {},
               const std::string& shown_path = "");
  ~VectorWriter();  // without commit(), removes everything
  VectorWriter(const VectorWriter&) = delete;
  VectorWriter& operator=(const VectorWriter&) = delete;

  // Starts a layer (ending the previous one).
  void begin_layer(const std::string& name, GeometryKind kind, const std::vector<FieldDef>& fields,
                   const LayerAbout& about = {});
  // Adds a feature to the current layer; values follow the layer's fields.
  void add_point(const Point2& p, const std::vector<FieldValue>& values);
  void add_polygon(const Polygon& polygon, const std::vector<FieldValue>& values);
  void add_polygon(const std::vector<Point2>& ring, const std::vector<FieldValue>& values);
  void add_line(const std::vector<Point2>& line, const std::vector<FieldValue>& values);
  // Adds a row without geometry (a GeometryKind::none layer).
  void add_row(const std::vector<FieldValue>& values);
  // Finishes the file and moves it into place.
  void commit();

 private:
  void add(OGRGeometry* g, const std::vector<FieldValue>& values);
  void end_layer();
  [[noreturn]] void fail(const std::string& what) const;
  std::string shown_name() const;  // the driver's, GeoPackage for GPKG

  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace isoquad
