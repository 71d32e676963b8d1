#include "gis/write_domain.h"

#include "gis/vector_writer.h"

namespace isoquad {

void write_domain_gpkg(const Domain& domain, const WriteDomainParams& params) {
  VectorWriter w(params.path, params.overwrite, domain.crs_wkt);
  w.begin_layer(params.layer, GeometryKind::polygon,
                {{"component", FieldType::integer},
                 {"area_m2", FieldType::real},
                 {"perimeter_m", FieldType::real},
                 {"num_holes", FieldType::integer},
                 {"num_vertices", FieldType::integer}});
  for (std::size_t i = 0; i < domain.polygons.size(); ++i) {
    const Polygon& p = domain.polygons[i];
    w.add_polygon(p, {FieldValue::integer(static_cast<long long>(i)), FieldValue::real(area(p)),
                      FieldValue::real(perimeter(p)),
                      FieldValue::integer(static_cast<long long>(p.holes.size())),
                      FieldValue::integer(static_cast<long long>(num_vertices(p)))});
  }
  w.commit();
}

}  // namespace isoquad
