// Property tests of the whole front end on the real Natural Earth samples.
#include "app/front_end.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "core/error.h"
#include "domain/narrow_features.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "support/geodesic.h"
#include "support/ring_checks.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

FrontEndOptions france(double simplify_m) {
  FrontEndOptions o;
  o.read.path = sample("france.shp");
  o.simplify_m = simplify_m;
  return o;
}

// The water domain of the brittany_land sample, as the README runs it.
FrontEndOptions brittany_water() {
  FrontEndOptions o;
  o.read.path = sample("brittany_land.shp");
  o.read.bbox = std::array<double, 4>{-5.3, 46.8, -1.95, 49.35};
  o.kind = DomainKind::water;
  o.simplify_m = 0.0;
  return o;
}

}  // namespace

TEST(FrontEnd, FranceAreaMatchesTheEllipsoid) {
  const FrontEndResult r = build_planar_domain(france(0.0));
  EXPECT_TRUE(r.summary.automatic_crs);
  EXPECT_EQ(r.summary.num_components, 1u);
  EXPECT_EQ(r.summary.num_holes, 1u);
  // Reference: the same rings on the WGS 84 ellipsoid.
  SourceData src = read_polygons(france(0.0).read);
  Polygon lonlat;
  lonlat.outer = src.polygons[0].rings[0];
  lonlat.holes.assign(src.polygons[0].rings.begin() + 1, src.polygons[0].rings.end());
  const double reference = geodesic_area_m2(lonlat);
  EXPECT_NEAR(reference / 1e6, 538714.0, 50.0);
  EXPECT_NEAR(r.summary.area_m2 / reference, 1.0, 0.005);
}

// A polygon drawn by its four corners in longitude and latitude, 10 W to 10 E and 80 to
// 85 N: its sides along the parallels are arcs round the pole once projected, and as
// chords between the corners it lost 2% of its area (159,441 km2 for 162,745). Its edges
// now follow their images.
TEST(FrontEnd, EdgesDrawnAlongParallelsFollowThemOnceProjected) {
  TempDir dir;
  const std::string path = dir.file("cap.geojson");
  write_file(path, geojson_polygons({"[[[-10,80],[10,80],[10,85],[-10,85],[-10,80]]]"}, ""));
  FrontEndOptions o;
  o.read.path = path;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_GT(num_vertices(r.domain), 40u);
  // The reference: the ring with its sides densified along the parallels and meridians.
  Ring lonlat;
  const Point2 corners[4] = {{-10, 80}, {10, 80}, {10, 85}, {-10, 85}};
  for (int side = 0; side < 4; ++side)
    for (int i = 0; i < 1000; ++i) {
      const Point2 a = corners[side], b = corners[(side + 1) % 4];
      lonlat.push_back({a.x + (b.x - a.x) * i / 1000.0, a.y + (b.y - a.y) * i / 1000.0});
    }
  const double reference = geodesic_area_m2(lonlat);
  EXPECT_NEAR(reference / 1e6, 162745.0, 5.0);
  EXPECT_NEAR(r.summary.area_m2 / reference, 1.0, 1e-3);
}

TEST(FrontEnd, FranceInLambert93) {
  FrontEndOptions o = france(0.0);
  o.project.dst_crs = "EPSG:2154";
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_FALSE(r.summary.automatic_crs);
  EXPECT_NE(r.summary.meshing_crs_name.find("Lambert-93"), std::string::npos);
  // Lambert-93 is conformal with a scale error below 0.1% over France.
  EXPECT_NEAR(r.summary.area_m2 / 1e6, 538392.0, 538392.0 * 0.002);
}

// An input in a projected CRS is meshed in it where that CRS is conformal and true to
// the ground's scale within 1% (UTM in its zone), so that the mesh's coordinates are its
// other data's; Web Mercator (not conformal on the ellipsoid) is not kept, and the
// summary says why; --dst-crs local asks for the automatic projection.
TEST(FrontEnd, AProjectedInputIsMeshedInItsCrsWhereThatIsTrueToTheGround) {
  FrontEndOptions o;
  o.read.path = source_dir() + "/tests/golden/graded_rectangle/input.geojson";
  o.read.src_crs = "EPSG:32631";
  FrontEndResult r = build_planar_domain(o);
  EXPECT_TRUE(r.summary.input_crs_kept);
  EXPECT_FALSE(r.summary.automatic_crs);
  EXPECT_EQ(r.summary.meshing_crs_name, "WGS 84 / UTM zone 31N");
  EXPECT_EQ(r.summary.input_crs_not_kept, "");
  const Ring drawn = read_polygons(o.read).polygons[0].rings[0];
  for (const Point2& p : r.domain.polygons[0].outer)  // the input's coordinates, untouched
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), p), drawn.end()) << p.x << " " << p.y;
  o.project.dst_crs = "local";
  r = build_planar_domain(o);
  EXPECT_FALSE(r.summary.input_crs_kept);
  EXPECT_TRUE(r.summary.automatic_crs);
  EXPECT_EQ(r.summary.input_crs_not_kept, "");

  o = FrontEndOptions();
  o.read.path = source_dir() + "/tests/golden/annulus/input.geojson";
  r = build_planar_domain(o);
  EXPECT_FALSE(r.summary.input_crs_kept);
  EXPECT_TRUE(r.summary.automatic_crs);
  EXPECT_NE(r.summary.input_crs_not_kept.find("not conformal"), std::string::npos)
      << r.summary.input_crs_not_kept;
}

// --dst-crs utm: the UTM zone of the domain's centre; a warning where the domain reaches
// beyond the zone's 1%; none for a polar domain.
TEST(FrontEnd, DstCrsUtmIsTheZoneOfTheDomainsCentre) {
  FrontEndOptions o = france(0.0);
  o.project.dst_crs = "utm";
  FrontEndResult r = build_planar_domain(o);
  EXPECT_EQ(r.summary.meshing_crs_name, "WGS 84 / UTM zone 31N");  // centred at 1.7 E
  for (const std::string& w : r.summary.warnings)
    EXPECT_EQ(w.find("--dst-crs utm"), std::string::npos) << w;
  TempDir dir;
  const std::string wide = dir.file("wide.geojson"), polar = dir.file("polar.geojson");
  write_file(wide, geojson_polygons({"[[[-25,40],[25,40],[25,50],[-25,50],[-25,40]]]"}));
  write_file(polar, geojson_polygons({"[[[-10,85],[10,85],[10,88],[-10,88],[-10,85]]]"}));
  o = FrontEndOptions();
  o.read.path = wide;
  o.project.dst_crs = "utm";
  r = build_planar_domain(o);
  EXPECT_EQ(r.summary.meshing_crs_name, "WGS 84 / UTM zone 31N");
  bool warned = false;
  for (const std::string& w : r.summary.warnings) warned = warned || w.find("--dst-crs utm (") == 0;
  EXPECT_TRUE(warned);
  o.read.path = polar;
  try {
    build_planar_domain(o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::crs);
    EXPECT_NE(std::string(e.what()).find("beyond UTM's 80 S to 84 N"), std::string::npos)
        << e.what();
  }
}

// An explicit --dst-crs far from the domain (a zone mistyped: UTM 10N, California's, for
// France) is warned of; the zone that holds it is not.
TEST(FrontEnd, ADstCrsFarFromTheDomainIsWarnedOf) {
  for (const auto& [crs, warned] :
       std::vector<std::pair<std::string, bool>>{{"EPSG:32610", true}, {"EPSG:32631", false}}) {
    FrontEndOptions o = france(0.0);
    o.project.dst_crs = crs;
    const FrontEndResult r = build_planar_domain(o);
    bool found = false;
    for (const std::string& w : r.summary.warnings)
      found = found || w.find("far outside the CRS's area of use") != std::string::npos;
    EXPECT_EQ(found, warned) << crs;
  }
}

// A CRS whose map ends at the antimeridian (EPSG:3857): a domain that reaches 180 from
// the west is projected where it lies (180 is not read as -180 there, the map's other
// edge), and one across 180 is refused rather than torn across the map; EPSG:3832
// (Mercator centred on 150 E) holds it whole, as the local projection does.
TEST(FrontEnd, ADomainTheCrsMapWouldTearIsRefused) {
  TempDir dir;
  const std::string east = dir.file("east.geojson"), across = dir.file("across.geojson");
  write_file(east, geojson_polygons({"[[[175,60],[180,60],[180,61],[175,61],[175,60]]]"}));
  write_file(across, geojson_polygons({"[[[178,-17],[182,-17],[182,-16],[178,-16],[178,-17]]]"}));
  FrontEndOptions o;
  o.read.path = east;
  o.project.dst_crs = "EPSG:3857";
  FrontEndResult r = build_planar_domain(o);
  // 5 x 1 degrees at 60.5 N: about 30,200 km2 on the ground, 4.1 times that in Mercator.
  EXPECT_NEAR(r.summary.area_m2 / (4.1 * 30.2e9), 1.0, 0.05);
  o.read.path = across;
  try {
    build_planar_domain(o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::crs);
    EXPECT_NE(std::string(e.what()).find("does not fit whole in the map of 'WGS 84 / "
                                         "Pseudo-Mercator'"),
              std::string::npos)
        << e.what();
  }
  // 4 x 1 degrees at 16.5 S: about 47,200 km2 on the ground, 1.09 times that in Mercator.
  for (const auto& [crs, k2] : {std::pair{"EPSG:3832", 1.09}, std::pair{"", 1.0}}) {
    o.project.dst_crs = crs;
    r = build_planar_domain(o);
    EXPECT_NEAR(r.summary.area_m2 / (k2 * 47.2e9), 1.0, 0.02) << crs;
  }
}

TEST(FrontEnd, SimplificationKeepsHolesAndNeverCrossesAndShrinksMonotonically) {
  std::size_t previous = SIZE_MAX;
  for (double tol : {0.0, 100.0, 1000.0, 5000.0, 20000.0}) {
    const FrontEndResult r = build_planar_domain(france(tol));
    EXPECT_EQ(r.summary.num_holes, 1u) << tol;
    EXPECT_EQ(find_crossing(r.domain), "") << tol;
    EXPECT_LT(r.summary.num_vertices_after, previous) << tol;
    previous = r.summary.num_vertices_after;
    // Simplification moves the boundary by at most the tolerance: the area changes by
    // at most about perimeter x tolerance.
    EXPECT_NEAR(r.summary.area_m2 / 538356e6, 1.0, 0.01 + r.summary.perimeter_m * tol / 5.38e11);
  }
}

TEST(FrontEnd, BrittanyWaterIsOnePolygonWithIslandHoles) {
  const FrontEndResult r = build_planar_domain(brittany_water());
  ASSERT_EQ(r.summary.num_components, 1u);
  EXPECT_EQ(r.summary.num_holes, 4u);  // Ouessant, Belle-Ile, Noirmoutier, Jersey
  EXPECT_EQ(find_crossing(r.domain), "");

  // Reference: the same difference by GDAL/GEOS through OGR's own geometry API,
  // projected to the same CRS.
  ensure_gdal_registered();
  GDALDataset* ds = static_cast<GDALDataset*>(
      GDALOpenEx(sample("brittany_land.shp").c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  OGRMultiPolygon land;
  for (auto& f : *ds->GetLayer(0)) land.addGeometry(f->GetGeometryRef());
  std::unique_ptr<OGRGeometry> land_union(land.UnionCascaded());
  OGRLinearRing box_ring;
  for (const Point2& p : densified_box({-5.3, 46.8, -1.95, 49.35}, 64)) box_ring.addPoint(p.x, p.y);
  box_ring.closeRings();
  OGRPolygon box;
  box.addRing(&box_ring);
  std::unique_ptr<OGRGeometry> sea(box.Difference(land_union.get()));
  OGRSpatialReference wgs, local;
  wgs.importFromEPSG(4326);
  wgs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  local.importFromWkt(r.domain.crs_wkt.c_str());
  local.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  sea->assignSpatialReference(&wgs);
  ASSERT_EQ(sea->transformTo(&local), OGRERR_NONE);
  const double reference = sea->toSurface()->get_Area();
  GDALClose(ds);
  EXPECT_NEAR(r.summary.area_m2 / reference, 1.0, 0.01);
  EXPECT_NEAR(r.summary.area_m2 / 1e6, 47160.0, 100.0);
}

TEST(FrontEnd, MinIslandAreaDropsSmallIslandsAndLargestKeepsOne) {
  FrontEndOptions o = brittany_water();
  o.min_island_area_m2 = 70e6;  // 70 km2: keeps Belle-Ile (85 km2) and Jersey (118 km2)
  FrontEndResult r = build_planar_domain(o);
  EXPECT_EQ(r.summary.num_holes, 2u);
  EXPECT_EQ(r.summary.dropped.num_holes_dropped, 2u);

  FrontEndOptions land;
  land.read.path = sample("brittany_land.shp");
  r = build_planar_domain(land);
  EXPECT_GT(r.summary.num_components, 3u);
  land.largest = true;
  const FrontEndResult largest = build_planar_domain(land);
  EXPECT_EQ(largest.summary.num_components, 1u);
  EXPECT_DOUBLE_EQ(largest.summary.area_m2, area(r.domain.polygons[0]));
}

TEST(FrontEnd, SizeSetsTheCleaningDefaults) {
  FrontEndOptions o = france(0.0);
  o.simplify_m.reset();
  o.target_size_m = 4000.0;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_DOUBLE_EQ(r.summary.simplify_m, 1000.0);
  EXPECT_DOUBLE_EQ(r.summary.min_island_area_m2, 16e6);
  // The Llivia enclave (12 km2) is under 16 km2.
  EXPECT_EQ(r.summary.num_holes, 0u);
  EXPECT_EQ(r.summary.dropped.num_holes_dropped, 1u);
}

TEST(FrontEnd, SameInputGivesIdenticalDomains) {
  const FrontEndResult a = build_planar_domain(france(1000.0));
  const FrontEndResult b = build_planar_domain(france(1000.0));
  ASSERT_EQ(num_vertices(a.domain), num_vertices(b.domain));
  EXPECT_EQ(a.domain.crs_wkt, b.domain.crs_wkt);
  for (std::size_t i = 0; i < a.domain.polygons[0].outer.size(); ++i)
    ASSERT_EQ(a.domain.polygons[0].outer[i], b.domain.polygons[0].outer[i]);
}

TEST(FrontEnd, GeographicDstCrsIsRejected) {
  FrontEndOptions o = france(0.0);
  o.project.dst_crs = "EPSG:4326";
  try {
    build_planar_domain(o);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::crs);
    EXPECT_NE(std::string(e.what()).find("not a projected CRS"), std::string::npos);
  }
}

TEST(FrontEnd, NoNarrowFeatureIsLeftAfterTheLastSimplification) {
  // At 15 km the Rade de Brest, filled up to its mouth, simplified to a wedge 2.6 km
  // wide and 21 km long that no quad could follow: the narrow-feature step runs again
  // on what the simplification leaves.
  FrontEndOptions o = france(0.0);
  o.simplify_m.reset();
  o.target_size_m = 15000.0;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_GT(r.summary.narrow.num_pieces, 0u);
  Domain again = r.domain;
  NarrowParams np;
  np.min_width_m = r.summary.min_width_m;
  // What the offsets alone move is far less than one square of the width.
  const NarrowResult n = remove_narrow_features(again, np);
  EXPECT_LT(n.area_removed_m2 + n.area_added_m2, 0.1 * np.min_width_m * np.min_width_m);
}

// Five strips of a spiky polygon (cut from a random star) at a size of 50 m: a spit cut
// at its base left a triangle of about 1 m2 as a component of its own, after the
// islands under --min-island-area (2,500 m2 here) had been dropped; the tiling could
// not cover it (a tile with two meta-vertices, six tilings in a row). No component or
// hole the front end returns is under that area.
TEST(FrontEnd, NoPieceUnderTheLeastAreaIsLeftAfterTheCuts) {
  TempDir dir;
  const std::vector<std::string> rings = {
      "[499290.98,4997875.0],[499280.57,4997875.0],[499375.0,4998161.11],[499375.0,4998117.13],"
      "[499290.98,4997875.0]",
      "[499253.1,4997875.0],[499251.08,4997875.0],[499270.82,4997942.58],[499245.44,4997875.0],"
      "[499239.14,4997875.0],[499370.55,4998250.0],[499375.0,4998250.0],[499375.0,4998215.01],"
      "[499253.1,4997875.0]",
      "[499228.96,4997875.0],[499224.68,4997875.0],[499226.38,4997885.1],[499222.42,4997875.0],"
      "[499214.79,4997875.0],[499350.28,4998250.0],[499368.87,4998250.0],[499228.96,4997875.0]",
      "[499243.5,4998151.47],[499124.36,4997875.0],[499116.46,4997875.0],[499270.1,4998250.0],"
      "[499284.7,4998250.0],[499243.5,4998151.47]",
      "[499000.0,4998012.16],[499000.0,4998033.5],[499026.99,4998091.85],[499000.0,4998049.07],"
      "[499000.0,4998088.79],[499083.06,4998250.0],[499120.71,4998250.0],[499000.0,4998012.16]"};
  std::vector<std::string> polygons;
  for (const std::string& r : rings) polygons.push_back("[[" + r + "]]");
  const std::string path = dir.file("strips.geojson");
  write_file(path, geojson_polygons(polygons, kUtm31nCrsMember));
  FrontEndOptions o;
  o.read.path = path;
  o.target_size_m = 50.0;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_GT(r.summary.spikes.num_cut_at_base, 0u);  // the cut that left the piece
  ASSERT_FALSE(r.domain.polygons.empty());
  for (const Polygon& p : r.domain.polygons) {
    EXPECT_GE(std::abs(signed_area(p.outer)), r.summary.min_island_area_m2);
    for (const Ring& h : p.holes) EXPECT_GE(std::abs(signed_area(h)), r.summary.min_island_area_m2);
  }
}

// Polygons that miss each other by a hair, far narrower than the narrow features'
// width: two islands 1 cm apart (a corner of one 1 cm from the other's side), and a lake
// 1 cm from the coast. The narrow features keep them (joining the islands or opening
// the lake changes the topology), and the background mesh would refine to their width
// (1 cm: 1.1 million vertices, 5 minutes); the hairline pass closes the gap and cuts the
// strip, with a warning naming the place. With --hairline 0 they stay, with a warning.
TEST(FrontEnd, HairlineGapsAndStripsAreClosedOrCut) {
  TempDir dir;
  const std::string islands = dir.file("islands.geojson"), lake = dir.file("lake.geojson");
  write_file(islands,
             geojson_polygons({"[[[500000,5000000],[510000,5000000],[510000,5010000],[500000,"
                               "5010000],[500000,5000000]]]",
                               "[[[510000.01,5002000],[515000.01,5002000],[515000.01,5007000],"
                               "[510000.01,5007000],[510000.01,5002000]]]"},
                              kUtm31nCrsMember));
  write_file(lake, geojson_polygons({"[[[500000,5000000],[510000,5000000],[510000,5010000],"
                                     "[500000,5010000],[500000,5000000]],[[500000.01,5002000],["
                                     "505000,5002000],[505000,5008000],[500000.01,5008000],["
                                     "500000.01,5002000]]]"},
                                    kUtm31nCrsMember));
  auto build = [](const std::string& path, std::optional<double> hairline) {
    FrontEndOptions o;
    o.read.path = path;
    o.target_size_m = 200.0;
    o.hairline_m = hairline;
    return build_planar_domain(o);
  };
  auto warned = [](const FrontEndResult& r, const std::string& text) {
    return std::any_of(r.summary.warnings.begin(), r.summary.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
  };
  const FrontEndResult a = build(islands, std::nullopt);
  EXPECT_EQ(a.summary.num_components, 1u);
  EXPECT_EQ(a.summary.narrow.num_hairline, 1u);
  EXPECT_EQ(a.summary.narrow.num_pieces_kept, 0u);
  EXPECT_TRUE(warned(a, "narrower than --hairline (1 m) closed"));
  EXPECT_TRUE(warned(a, "near (510000"));
  // Both squares whole, joined near the corner, and not much more.
  EXPECT_NEAR(a.summary.area_m2, 125e6, 0.001 * 125e6);
  EXPECT_TRUE(domain_contains(a.domain, {510000.005, 5004500}));

  const FrontEndResult b = build(lake, std::nullopt);
  EXPECT_EQ(b.summary.num_holes, 0u);  // the lake is a bay
  EXPECT_EQ(b.summary.narrow.num_hairline, 1u);
  EXPECT_FALSE(domain_contains(b.domain, {500000.005, 5005000}));
  EXPECT_NEAR(b.summary.area_m2, 100e6 - 30e6, 0.001 * 70e6);

  // The gap between the islands needs nothing of the quads: no warning; the strip of
  // land between the lake and the sea does.
  const FrontEndResult c = build(islands, 0.0);
  EXPECT_EQ(c.summary.num_components, 2u);
  EXPECT_EQ(c.summary.narrow.num_hairline, 0u);
  EXPECT_EQ(c.summary.narrow.num_pieces_kept, 1u);
  EXPECT_FALSE(warned(c, "kept"));
  const FrontEndResult d = build(lake, 0.0);
  EXPECT_EQ(d.summary.num_holes, 1u);
  EXPECT_TRUE(warned(d, "1 part(s) of the domain narrower than --min-width (50 m) kept"));
  // The place in the meshing CRS (UTM 31N here) and in latitude and longitude.
  EXPECT_TRUE(warned(d,
                     "near (500000.005, 5005000) in the meshing CRS, 45.19849 N 3.00000 E, "
                     "about 0.01 m wide"));
}

// --align: of a file of lines, only the runs of segments near the domain's box are kept
// (a file over a continent is walked only where the domain is), each with its line.
TEST(FrontEnd, AlignLinesAreKeptWhereTheyComeNearTheDomain) {
  TempDir dir;
  const std::string lines = dir.file("lines.geojson");
  // Corsica lies in lon 8.5..9.6, lat 41.3..43.1. Line 0 crosses it from far west to far
  // east; line 1 lies in Spain; line 2 starts in Corsica's north, goes away to the east
  // and comes back to its south.
  write_file(lines,
             R"({"type":"FeatureCollection","features":[)"
             R"({"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":)"
             R"([[0,42],[5,42.1],[9,42.2],[13,42.3],[20,42.4]]}},)"
             R"({"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":)"
             R"([[-4,40],[-3,40.5]]}},)"
             R"({"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":)"
             R"([[9.2,42.9],[20,43.5],[20,41],[9.2,41.6]]}}]})");
  FrontEndOptions o;
  o.read.path = sample("corsica.shp");
  o.align_path = lines;
  const FrontEndResult r = build_planar_domain(o);
  EXPECT_EQ(r.summary.align_num_lines, 3u);
  ASSERT_EQ(r.align_lines.size(), r.align_line_of.size());
  std::vector<int> pieces_of(3, 0);
  for (int l : r.align_line_of) ++pieces_of.at(l);
  EXPECT_EQ(pieces_of, (std::vector<int>{1, 0, 2}));
  // Every segment kept meets the domain's box widened by 1% of its diagonal.
  const std::array<double, 4> box = bounding_box(r.domain);
  const double margin = 0.01 * std::hypot(box[2] - box[0], box[3] - box[1]);
  for (const auto& piece : r.align_lines) {
    ASSERT_GE(piece.size(), 2u);
    for (std::size_t i = 0; i + 1 < piece.size(); ++i) {
      const Point2 &a = piece[i], &b = piece[i + 1];
      EXPECT_TRUE(std::max(a.x, b.x) >= box[0] - margin && std::min(a.x, b.x) <= box[2] + margin &&
                  std::max(a.y, b.y) >= box[1] - margin && std::min(a.y, b.y) <= box[3] + margin);
    }
  }
}
