#include "gis/write_domain.h"

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>

#include "core/error.h"
#include "gis/atomic_output.h"
#include "gis/gdal_env.h"

namespace isoquad {

namespace {

OGRLinearRing to_ogr(const Ring& r) {
  OGRLinearRing lr;
  lr.setNumPoints(static_cast<int>(r.size() + 1), FALSE);
  for (std::size_t i = 0; i <= r.size(); ++i) {
    const Point2& p = r[i % r.size()];
    lr.setPoint(static_cast<int>(i), p.x, p.y);
  }
  return lr;
}

}  // namespace

void write_domain_gpkg(const Domain& domain, const WriteDomainParams& params) {
  ensure_gdal_registered();
  AtomicOutput out(params.path, params.overwrite);
  auto fail = [&](const std::string& what, const GdalErrorCapture& c) {
    throw Error(ErrorClass::output, "write",
                "'" + params.path + "': " + what +
                    (c.last_message().empty() ? "" : ": " + c.last_message()));
  };
  {
    // Same input, same bytes: GeoPackage stores a "last change" time, which we pin
    // unless the user sets OGR_CURRENT_DATE.
    CPLConfigOptionSetter fixed_date("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z", true);
    GdalErrorCapture capture;
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (!driver) fail("GDAL has no GeoPackage driver", capture);
    struct Closer {
      void operator()(GDALDataset* d) const { GDALClose(d); }
    };
    std::unique_ptr<GDALDataset, Closer> ds(
        driver->Create(out.temp_path().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds) fail("cannot create the GeoPackage", capture);
    OGRSpatialReference srs;
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    srs.importFromWkt(domain.crs_wkt.c_str());
    OGRLayer* layer = ds->CreateLayer(params.layer.c_str(), &srs, wkbPolygon, nullptr);
    if (!layer) fail("cannot create layer '" + params.layer + "'", capture);
    OGRFieldDefn f_comp("component", OFTInteger), f_area("area_m2", OFTReal),
        f_perim("perimeter_m", OFTReal), f_holes("num_holes", OFTInteger),
        f_verts("num_vertices", OFTInteger);
    for (OGRFieldDefn* f : {&f_comp, &f_area, &f_perim, &f_holes, &f_verts})
      if (layer->CreateField(f) != OGRERR_NONE) fail("cannot create fields", capture);
    if (layer->StartTransaction() != OGRERR_NONE) fail("cannot start a transaction", capture);
    for (std::size_t i = 0; i < domain.polygons.size(); ++i) {
      const Polygon& p = domain.polygons[i];
      OGRPolygon poly;
      OGRLinearRing outer = to_ogr(p.outer);
      poly.addRing(&outer);
      for (const Ring& h : p.holes) {
        OGRLinearRing hole = to_ogr(h);
        poly.addRing(&hole);
      }
      OGRFeature feature(layer->GetLayerDefn());
      feature.SetField("component", static_cast<int>(i));
      feature.SetField("area_m2", area(p));
      feature.SetField("perimeter_m", perimeter(p));
      feature.SetField("num_holes", static_cast<int>(p.holes.size()));
      feature.SetField("num_vertices", static_cast<int>(num_vertices(p)));
      feature.SetGeometry(&poly);
      if (layer->CreateFeature(&feature) != OGRERR_NONE) fail("cannot write a feature", capture);
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("cannot commit the layer", capture);
    CPLErrorReset();
    ds.reset();  // closes the file; GDAL reports failures through its error state
    if (CPLGetLastErrorType() == CE_Failure) fail("cannot finish the GeoPackage", capture);
  }
  out.commit();
}

}  // namespace isoquad
