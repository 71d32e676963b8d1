// read_mesh on files written by hand as other tools write them (node ids out of order,
// mixed triangles and quadrangles, nodes after elements, Fortran exponents, CRLF), and
// its errors: each names the file and the line.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <algorithm>
#include <cstdint>
#include <sstream>

#include <cpl_conv.h>
#include <cpl_string.h>

#include "core/error.h"
#include "gis/mesh_outline.h"
#include "gis/read_mesh.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

// The error read_mesh gives for `text` in a file of that name, or "" when it reads it.
std::string read_error(const TempDir& dir, const std::string& name, const std::string& text) {
  write_file(dir.file(name), text);
  try {
    read_mesh(dir.file(name));
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::input) << e.what();
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ReadMesh, Gr3WithMixedElementsAndIdsOutOfOrder) {
  TempDir dir;
  // Nodes numbered 10, 30, 20, 40, 50: the elements refer to the ids, not the order.
  write_file(dir.file("hgrid.gr3"),
             "grid\r\n3 5\r\n10 0 0 -1\r\n30 1.0D+01 0 2\r\n20 10 10 3\r\n40 0 10 4\r\n"
             "50 2e1 5 1\r\n1 4 10 30 20 40\r\n2 3 30 50 20\r\n3 3 10 30 40\r\n"
             "1 = Number of open boundaries\r\n2 = Total number of open boundary nodes\r\n"
             "2 0 = Number of nodes for open boundary 1\r\n30\r\n50\r\n"
             "1 = Number of land boundaries\r\n");
  const ReadMesh m = read_mesh(dir.file("hgrid.gr3"));
  EXPECT_EQ(m.open_boundaries, (std::vector<std::vector<int>>{{1, 4}}));
  // The land section ends after its count: left, with a note.
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("its land boundaries are not read"), std::string::npos);
  EXPECT_EQ(m.format, "gr3");
  ASSERT_EQ(m.points.size(), 5u);
  EXPECT_EQ(m.points[1].x, 10.0);  // the Fortran exponent
  EXPECT_EQ(m.points[4].x, 20.0);
  ASSERT_EQ(m.quads.size(), 1u);
  EXPECT_EQ(m.quads[0], (std::array<int, 4>{0, 1, 2, 3}));
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 4, 2}));
  EXPECT_TRUE(m.crs.empty());
  // The file's own numbers, in the order of the nodes and elements.
  EXPECT_EQ(m.point_ids, (std::vector<long long>{10, 30, 20, 40, 50}));
  EXPECT_EQ(m.quad_ids, (std::vector<long long>{1}));
  EXPECT_EQ(m.triangle_ids, (std::vector<long long>{2, 3}));
  EXPECT_EQ(file_number(m.point_ids, 2), 20);
  EXPECT_EQ(file_number({}, 2), 3);
}

// ADCIRC's land boundaries: the flux one (IBTYPE 22, a river) open after the open ones,
// the others (20, and a barrier of 3 with its height and coefficient) left as land.
TEST(ReadMesh, Fort14FluxBoundariesAreOpen) {
  TempDir dir;
  write_file(dir.file("fort.14"),
             "grid\n2 6\n1 0 0 5\n2 10 0 5\n3 20 0 5\n4 20 10 5\n5 10 10 5\n6 0 10 5\n"
             "1 4 1 2 5 6\n2 4 2 3 4 5\n1 = NOPE\n2 = NETA\n2 = NVDLL\n3\n4\n"
             "3 = NBOU\n7 = NVEL\n2 22 = river\n4\n5\n2 3 = barrier\n5 1.0 1.0\n6 1.0 1.0\n"
             "3 20 = land\n6\n1\n2\n");
  const ReadMesh m = read_mesh(dir.file("fort.14"));
  EXPECT_TRUE(m.notes.empty());
  EXPECT_EQ(m.num_flux_boundaries, 1u);
  EXPECT_EQ(m.open_boundaries, (std::vector<std::vector<int>>{{2, 3}, {3, 4}}));
}

TEST(ReadMesh, TwoDmWithNodesAfterElements) {
  TempDir dir;
  write_file(dir.file("m.2dm"),
             "MESH2D\nMESHNAME \"test\"\nE4Q 1 1 2 3 4 1\nE3T 2 2 5 3 1\nND 1 0 0 0\n"
             "ND 2 10 0 0\nND 3 10 10 0\nND 4 0 10 0\nND 5 20 5 0\nNS 1 2 -5\n"
             "NS 3\nNS -4 Open_north\n");
  ReadMesh m = read_mesh(dir.file("m.2dm"));
  EXPECT_EQ(m.quads.size(), 1u);
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.points.size(), 5u);
  // The nodestrings, numbered from 1; the second over two cards, named as BASEMENT does,
  // and open by its name.
  ASSERT_EQ(m.curve_groups.size(), 2u);
  EXPECT_EQ(m.curve_groups[0].tag, 1);
  EXPECT_EQ(m.curve_groups[0].name, "");
  EXPECT_EQ(m.curve_groups[0].edges, (std::vector<std::array<int, 2>>{{0, 1}, {1, 4}}));
  EXPECT_EQ(m.curve_groups[1].name, "Open_north");
  EXPECT_EQ(m.open_boundaries, (std::vector<std::vector<int>>{{2, 3}}));
  open_boundaries_from_groups(m, {"1"}, "m.2dm");
  EXPECT_EQ(m.open_boundaries, (std::vector<std::vector<int>>{{0, 1, 4}}));
}

TEST(ReadMesh, MikeMeshWithTrianglesAndLonLat) {
  TempDir dir;
  write_file(dir.file("m.mesh"),
             "100079 1000 5 LONG/LAT\n1 0 0 -1 1\n2 1 0 -1 1\n3 1 1 -1 1\n4 0 1 -1 1\n"
             "5 2 0.5 -1 1\n2 4 25\n1 1 2 3 4\n2 2 5 3 0\n");
  const ReadMesh m = read_mesh(dir.file("m.mesh"));
  EXPECT_EQ(m.crs, "EPSG:4326");
  EXPECT_EQ(m.quads.size(), 1u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 4, 2}));
}

TEST(ReadMesh, Msh41WithBlocksOfSeveralTypes) {
  TempDir dir;
  write_file(dir.file("m.msh"),
             "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n2 5 1 7\n"
             "2 1 0 4\n1\n2\n3\n4\n0 0 0\n10 0 0\n10 10 0\n0 10 0\n"
             "2 2 0 1\n7\n20 5 0\n$EndNodes\n$Elements\n3 3 1 3\n"
             "1 1 1 1\n1 1 2\n2 1 3 1\n2 1 2 3 4\n2 2 2 1\n3 2 7 3\n$EndElements\n");
  const ReadMesh m = read_mesh(dir.file("m.msh"));
  EXPECT_EQ(m.points.size(), 5u);
  ASSERT_EQ(m.quads.size(), 1u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 4, 2}));
  EXPECT_EQ(m.num_skipped_elements, 1u);
  // The elements' tags, the line's (1) skipped with it; the nodes' tags.
  EXPECT_EQ(m.quad_ids, (std::vector<long long>{2}));
  EXPECT_EQ(m.triangle_ids, (std::vector<long long>{3}));
  EXPECT_EQ(m.point_ids, (std::vector<long long>{1, 2, 3, 4, 7}));
}

// An element number given twice names no one element: the elements are numbered in
// order (as SCHISM and ADCIRC read a .gr3's), with a note; the messages about nodes say
// the file's numbers.
TEST(ReadMesh, ElementNumbersGivenTwiceAreNumberedInOrder) {
  TempDir dir;
  write_file(dir.file("m.2dm"),
             "MESH2D\nND 10 0 0 0\nND 20 10 0 0\nND 30 10 10 0\nND 40 0 10 0\nND 50 20 5 0\n"
             "E4Q 7 10 20 30 40 1\nE3T 7 20 50 30 1\n");
  const ReadMesh m = read_mesh(dir.file("m.2dm"));
  EXPECT_TRUE(m.quad_ids.empty());
  EXPECT_TRUE(m.triangle_ids.empty());
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("element number 7 is given to two elements"), std::string::npos)
      << m.notes[0];
  write_file(dir.file("three.2dm"),
             "MESH2D\nND 10 0 0 0\nND 20 10 0 0\nND 30 10 10 0\nND 40 0 10 0\nND 50 5 -5 0\n"
             "E4Q 1 10 20 30 40 1\nE3T 2 10 20 50 1\nE3T 3 20 10 40 1\n");
  const ReadMesh three = read_mesh(dir.file("three.2dm"));
  try {
    mesh_outline(three.points, three.quads, three.triangles, "three.2dm", three.point_ids);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the edge between nodes 10 and 20 is a side of three"),
              std::string::npos)
        << e.what();
  }
}

namespace {

// Two quads side by side, 20 x 10: the right side in group 11 "open_1", the top in 12
// "OpenSea" (two open groups that meet at node 4), the rest in 1 "land", and the line
// between the quads in group 5 (no name in 2.2, none at all in 4.1).
const char* const kMsh22Groups =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n4\n1 1 \"land\"\n"
    "1 11 \"open_1\"\n1 12 \"OpenSea\"\n2 3 \"domain\"\n$EndPhysicalNames\n$Nodes\n6\n"
    "1 0 0 0\n2 10 0 0\n3 20 0 0\n4 20 10 0\n5 10 10 0\n6 0 10 0\n$EndNodes\n$Elements\n9\n"
    "1 1 2 11 1 3 4\n2 1 2 12 2 4 5\n3 1 2 12 2 5 6\n4 1 2 1 3 6 1\n5 1 2 1 3 1 2\n"
    "6 1 2 1 3 2 3\n7 1 2 5 4 2 5\n8 3 2 3 1 1 2 5 6\n9 3 2 3 1 2 3 4 5\n$EndElements\n";
const char* const kMsh41Groups =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n4\n1 1 \"land\"\n"
    "1 11 \"open_1\"\n1 12 \"OpenSea\"\n2 3 \"domain\"\n$EndPhysicalNames\n$Entities\n"
    "1 4 1 0\n1 0 0 0 0\n1 20 0 0 20 10 0 1 11 0\n2 0 10 0 20 10 0 1 12 0\n"
    "3 0 0 0 20 10 0 1 1 0\n4 10 0 0 10 10 0 0 0\n1 0 0 0 20 10 0 1 3 4 1 2 3 4\n"
    "$EndEntities\n$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n0 0 0\n10 0 0\n20 0 0\n"
    "20 10 0\n10 10 0\n0 10 0\n$EndNodes\n$Elements\n5 9 1 9\n1 1 1 1\n1 3 4\n1 2 1 2\n"
    "2 4 5\n3 5 6\n1 3 1 3\n4 6 1\n5 1 2\n6 2 3\n1 4 1 1\n7 2 5\n2 1 3 2\n8 1 2 5 6\n"
    "9 2 3 4 5\n$EndElements\n";

std::vector<std::vector<int>> sorted_runs(std::vector<std::vector<int>> runs) {
  std::sort(runs.begin(), runs.end());
  return runs;
}

std::string groups_error(ReadMesh& m, const std::vector<std::string>& groups) {
  try {
    open_boundaries_from_groups(m, groups, "m.msh");
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::usage) << e.what();
    return e.what();
  }
  return "";
}

}  // namespace

// The open boundaries of a .msh: the outline's runs along the lines of the groups named
// open... (each group a run of its own where two meet), or of the groups given.
TEST(ReadMesh, MshPhysicalGroupsOfCurvesGiveTheOpenBoundaries) {
  TempDir dir;
  for (const char* text : {kMsh22Groups, kMsh41Groups}) {
    write_file(dir.file("m.msh"), text);
    ReadMesh m = read_mesh(dir.file("m.msh"));
    EXPECT_EQ(m.quads.size(), 2u);
    EXPECT_EQ(m.num_skipped_elements, 7u);
    EXPECT_EQ(sorted_runs(m.open_boundaries), (std::vector<std::vector<int>>{{2, 3}, {3, 4, 5}}));
    EXPECT_EQ(m.curve_groups.size(), text == kMsh22Groups ? 4u : 3u);
    EXPECT_EQ(m.curve_groups.front().name, "land");
    open_boundaries_from_groups(m, {"land"}, "m.msh");
    EXPECT_EQ(m.open_boundaries, (std::vector<std::vector<int>>{{5, 0, 1, 2}}));
    open_boundaries_from_groups(m, {"11", "1"}, "m.msh");  // tags
    EXPECT_EQ(sorted_runs(m.open_boundaries),
              (std::vector<std::vector<int>>{{2, 3}, {5, 0, 1, 2}}));
    EXPECT_NE(groups_error(m, {"sea"})
                  .find("no physical group of curves 'sea' (it has 1 \"land\", " +
                        std::string(text == kMsh22Groups ? "5, " : "") +
                        "11 \"open_1\", 12 \"OpenSea\")"),
              std::string::npos);
  }
  write_file(dir.file("m.msh"), kMsh22Groups);
  ReadMesh m = read_mesh(dir.file("m.msh"));
  EXPECT_NE(groups_error(m, {"5"}).find(
                "no line of physical group of curves 5 lies on the mesh's outline"),
            std::string::npos);
  m.format = "gr3";
  EXPECT_NE(groups_error(m, {"land"}).find("neither a Gmsh .msh nor an SMS .2dm"),
            std::string::npos);
}

// D-Flow FM's older net file: NetNode_x, NetNode_y and NetElemNode (numbered from 1,
// missing corners as the fill value), its CRS in projected_coordinate_system's epsg.
TEST(ReadMesh, DflowfmNetFileWithATriangleAndAQuad) {
  TempDir dir;
  const std::string path = dir.file("m_net.nc");
  int nc = -1, dn = -1, de = -1, d4 = -1, vx = -1, vy = -1, ve = -1, vc = -1;
  ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_dim(nc, "nNetNode", 5, &dn);
  nc_def_dim(nc, "nNetElem", 2, &de);
  nc_def_dim(nc, "nNetElemMaxNode", 4, &d4);
  nc_def_var(nc, "NetNode_x", NC_DOUBLE, 1, &dn, &vx);
  nc_def_var(nc, "NetNode_y", NC_DOUBLE, 1, &dn, &vy);
  const int dims[2] = {de, d4};
  nc_def_var(nc, "NetElemNode", NC_INT, 2, dims, &ve);
  const int fill = -999;
  nc_put_att_int(nc, ve, "_FillValue", NC_INT, 1, &fill);
  nc_def_var(nc, "projected_coordinate_system", NC_INT, 0, nullptr, &vc);
  const int epsg = 32631;
  nc_put_att_int(nc, vc, "epsg", NC_INT, 1, &epsg);
  nc_enddef(nc);
  const double x[5] = {0, 10, 10, 0, 20}, y[5] = {0, 0, 10, 10, 5};
  const int cells[8] = {1, 2, 3, 4, 2, 5, 3, -999};
  nc_put_var_double(nc, vx, x);
  nc_put_var_double(nc, vy, y);
  nc_put_var_int(nc, ve, cells);
  nc_close(nc);
  const ReadMesh m = read_mesh(path);
  EXPECT_EQ(m.format, "nc");
  EXPECT_EQ(m.crs, "EPSG:32631");
  ASSERT_EQ(m.quads.size(), 1u);
  EXPECT_EQ(m.quads[0], (std::array<int, 4>{0, 1, 2, 3}));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 4, 2}));
  EXPECT_TRUE(is_mesh_file(path));
  // Not netCDF, or netCDF without a mesh.
  write_file(dir.file("text.nc"), "not netcdf\n");
  EXPECT_THROW(read_mesh(dir.file("text.nc")), Error);
  EXPECT_TRUE(is_mesh_file(dir.file("text.nc")));  // for the mesh reader to say what is wrong
  ASSERT_EQ(nc_create(dir.file("empty.nc").c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_close(nc);
  // Where a mesh or a raster may be given (INPUT, --bathymetry), a netCDF file without a
  // mesh is a grid for GDAL (GEBCO's), one with UGRID's mesh topology a mesh.
  EXPECT_FALSE(is_mesh_file(dir.file("empty.nc")));
  ASSERT_EQ(nc_create(dir.file("ugrid.nc").c_str(), NC_CLOBBER, &nc), NC_NOERR);
  nc_def_var(nc, "mesh", NC_INT, 0, nullptr, &vc);
  nc_put_att_text(nc, vc, "cf_role", 13, "mesh_topology");
  nc_close(nc);
  EXPECT_TRUE(is_mesh_file(dir.file("ugrid.nc")));
  try {
    read_mesh(dir.file("empty.nc"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no 2D mesh"), std::string::npos) << e.what();
  }
}

// Elements as polygons (GeoJSON here): corners at the same coordinates are one node;
// the layer's CRS; a pentagon stops the reading, naming the feature.
TEST(ReadMesh, PolygonLayerOfTrianglesAndQuadrangles) {
  TempDir dir;
  write_file(dir.file("m.geojson"), geojson_polygons({"[[[0,0],[10,0],[10,10],[0,10],[0,0]]]",
                                                      "[[[10,0],[20,5],[10,10],[10,0]]]"},
                                                     kUtm31nCrsMember));
  const ReadMesh m = read_mesh(dir.file("m.geojson"));
  EXPECT_EQ(m.format, "polygons");
  EXPECT_EQ(m.points.size(), 5u);
  ASSERT_EQ(m.quads.size(), 1u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{1, 4, 2}));
  EXPECT_NE(m.crs.find("32631"), std::string::npos);
  write_file(dir.file("p.geojson"),
             geojson_polygons({"[[[0,0],[10,0],[10,10],[0,10],[0,0]]]",
                               "[[[10,0],[20,0],[25,5],[20,10],[10,10],[10,0]]]"}));
  try {
    read_mesh(dir.file("p.geojson"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("feature 1 has 5 corners"), std::string::npos) << e.what();
  }
  // Polygons and one-part MultiPolygons in one GeoJSON: a layer of both types.
  write_file(dir.file("mixed.geojson"),
             R"({"type":"FeatureCollection","features":[)"
             R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon",)"
             R"("coordinates":[[[0,0],[10,0],[10,10],[0,10],[0,0]]]}},)"
             R"({"type":"Feature","properties":{},"geometry":{"type":"MultiPolygon",)"
             R"("coordinates":[[[[10,0],[20,0],[20,10],[10,10],[10,0]]]]}}]})");
  const ReadMesh mixed = read_mesh(dir.file("mixed.geojson"));
  EXPECT_EQ(mixed.quads.size(), 2u);
  EXPECT_EQ(mixed.points.size(), 6u);
}

// A Selafin file as little-endian machines write it (single precision, SERAFIN): two
// triangles of a unit square, its origin (IPARAM 3 and 4) added to the coordinates.
TEST(ReadMesh, SelafinLittleEndianSinglePrecision) {
  std::string file;
  auto record = [&file](const std::string& bytes) {
    const std::uint32_t n = static_cast<std::uint32_t>(bytes.size());
    const std::string length(reinterpret_cast<const char*>(&n), 4);  // this machine's order
    file += length + bytes + length;
  };
  auto ints = [](std::vector<std::int32_t> v) {
    return std::string(reinterpret_cast<const char*>(v.data()), 4 * v.size());
  };
  auto floats = [](std::vector<float> v) {
    return std::string(reinterpret_cast<const char*>(v.data()), 4 * v.size());
  };
  ASSERT_EQ(ints({1})[0], 1) << "a little-endian machine";
  record(std::string(72, 'T') + "SERAFIN ");
  record(ints({1, 0}));
  record(std::string(32, 'B'));
  record(ints({1, 0, 1000, 2000, 0, 0, 0, 0, 0, 0}));
  record(ints({2, 4, 3, 1}));
  record(ints({1, 2, 3, 1, 3, 4}));
  record(ints({1, 2, 3, 4}));
  record(floats({0, 1, 1, 0}));
  record(floats({0, 0, 1, 1}));
  TempDir dir;
  write_file(dir.file("le.slf"), file);
  const ReadMesh m = read_mesh(dir.file("le.slf"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.points[2].x, 1001.0);
  EXPECT_EQ(m.points[2].y, 2001.0);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 2, 3}));
}

TEST(ReadMesh, ErrorsNameTheFileAndTheLine) {
  TempDir dir;
  EXPECT_NE(read_error(dir, "a.gr3", "grid\n1 3\n1 0 0 0\n2 1 0 0\n3 1 1 0\n1 3 1 2 9\n")
                .find("a.gr3' line 6: element 1 has node 9, which is not among the file's nodes"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "b.gr3", "grid\n1 3\n1 0 0 0\n2 1 0 0\n")
                .find("b.gr3': the file ends at line 4"),
            std::string::npos);
  // Counts far beyond what the file holds (a damaged header) reserve nothing: the file
  // ends where the count says a node should follow.
  EXPECT_NE(read_error(dir, "h.gr3", "grid\n4 2000000000\n")
                .find("h.gr3': the file ends at line 2 where node 1 of 2000000000 should follow"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "h.msh",
                       "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4000000000 1 "
                       "4000000000\n2 1 0 4000000000\n")
                .find("h.msh': the file ends at line 6 where a node tag should follow"),
            std::string::npos);
  // The open boundaries: cut short, or with a node the file does not have.
  const std::string tri = "grid\n1 3\n1 0 0 0\n2 1 0 0\n3 1 1 0\n1 3 1 2 3\n";
  EXPECT_NE(read_error(dir, "f.gr3", tri + "1 = Number of open boundaries\n")
                .find("f.gr3': the file ends at line 7 where the total number of open boundary "
                      "nodes should follow"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "f.gr3", tri + "1 = Number of open boundaries\n")
                .find("is the file cut short, or does it have more than its header counts?"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "g.gr3", tri + "1\n2\n2\n1\n7\n")
                .find("g.gr3' line 11: open boundary 1 has node 7, which is not among the file's "
                      "nodes"),
            std::string::npos);
  // A header that counts one element of two: the second read as the open boundaries,
  // and the message says where they began.
  EXPECT_NE(read_error(dir, "n.gr3",
                       "grid\n1 4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n1 3 1 2 3\n2 3 1 3 4\n")
                .find("(the open boundaries begin after the header's 1 elements and 4 nodes: "
                      "is the file cut short, or does it have more than its header counts?)"),
            std::string::npos);
  // Files cut short (a copy or a write that stopped): said so, not "not a VTK file".
  EXPECT_NE(read_error(dir, "cut.gr3", "grid\n1 3\n1 0 0 0\n2 1")
                .find("cut.gr3' line 4: expected y (the file ends there, in the middle of a "
                      "line: was it written or copied whole?)"),
            std::string::npos);
  // Cut at a line's end: the line is whole, and not said to be cut.
  EXPECT_EQ(read_error(dir, "cut2.gr3", "grid\n1 3\n1 0 0 0\n2 1\n").find("middle of a line"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "cut2.gr3", "grid\n1 3\n1 0 0 0\n2 1\n").find("line 4: expected y"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "cut.vtu",
                       "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"><Unstruc")
                .find("cut.vtu': an incomplete or damaged VTK XML file (Parse error"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "not.vtu", "<?xml version=\"1.0\"?>\n<other/>\n")
                .find("not.vtu': not a VTK XML file (no VTKFile element)"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "cut.nc", std::string("\x89HDF\r\n\x1a\n\0\0\0", 11))
                .find("cut.nc': an incomplete or damaged netCDF file (NetCDF: "),
            std::string::npos);
  EXPECT_NE(read_error(dir, "not.nc", "grid\n").find("not.nc': not a netCDF file (NetCDF: "),
            std::string::npos);
  // A header that counts more elements than the file has: the boundaries' first line
  // read as an element, and the message says so.
  EXPECT_NE(read_error(dir, "m.gr3",
                       "grid\n3 4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n1 3 1 2 3\n2 3 1 3 4\n"
                       "0 = Number of open boundaries\n0 = Total number of open boundary nodes\n")
                .find("(the header counts 3 elements, and the file's elements seem to end after "
                      "2: does the header count more than it has?)"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "c.gr3", "grid\n1 3\n1 0 0 0\n2 1 x 0\n3 1 1 0\n1 3 1 2 3\n")
                .find("line 4: expected y, a number, found 'x'"),
            std::string::npos);
  // A damaged byte shows as '?', a long word cut.
  const std::string damaged = read_error(
      dir, "c2.gr3",
      "grid\n1 3\n1 0 0 0\n2 1 \xeb\x01" + std::string(40, '7') + " 0\n3 1 1 0\n1 3 1 2 3\n");
  EXPECT_NE(damaged.find("found '??" + std::string(30, '7') + "...'"), std::string::npos)
      << damaged;
  EXPECT_NE(
      read_error(dir, "d.gr3", "grid\n1 4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n1 5 1 2 3 4 1\n")
          .find("line 7: element 1 has 5 nodes"),
      std::string::npos);
  EXPECT_NE(read_error(dir, "e.gr3", "grid\n1 3\n1 0 0 0\n2 1 0 0\n3 1 1 0\n1 3 1 2 2\n")
                .find("element 1 has the same node twice"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "f.2dm", "MESH2D\nND 1 0 0 0\nE6T 1 1 1 1 1 1 1 1\n")
                .find("line 3: element card E6T"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "g.2dm", "MESH2D\nE3T 1 1 2 3 1\nND 1 0 0 0\nND 2 1 0 0\n")
                .find("g.2dm' line 2: element 1 has node 3, which is not among the ND cards"),
            std::string::npos);
  EXPECT_NE(
      read_error(dir, "h.msh", "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n").find("a binary .msh"),
      std::string::npos);
  EXPECT_NE(read_error(dir, "i.msh",
                       "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n"
                       "2 1 0 0\n3 1 1 0\n$EndNodes\n$Elements\n1\n1 9 2 0 1 1 2 3 1 2 3\n"
                       "$EndElements\n")
                .find("line 12: Gmsh element type 9"),
            std::string::npos);
  EXPECT_NE(read_error(dir, "j.msh", "hello\n").find("no $MeshFormat section"), std::string::npos);
  EXPECT_NE(read_error(dir, "s.slf", "hello\n").find("not a Selafin file"), std::string::npos);
  // A Selafin title record (big-endian length 80) and nothing after it.
  EXPECT_NE(read_error(dir, "t.slf",
                       std::string("\0\0\0P", 4) + std::string(80, ' ') + std::string("\0\0\0P", 4))
                .find("the file ends before the numbers of variables"),
            std::string::npos);
  EXPECT_NE(
      read_error(dir, "k.mesh", "100079 1000 3 LONG/LAT\n1 0 0 0 1\n2 1 0 0 1\n3 1 1 0 1\n1 5 25\n")
          .find("elements of 5 nodes"),
      std::string::npos);
  EXPECT_NE(read_error(dir, "l.2dm", "MESH2D\nND 1 0 0 0\n")
                .find("the mesh has no triangle or quadrangle"),
            std::string::npos);
  // Not a mesh format, or no such file.
  try {
    read_mesh(dir.file("m.txt"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::usage);
  }
  try {
    read_mesh(dir.file("missing.gr3"));
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.gr3': no such mesh file"), std::string::npos);
  }
}

namespace {

// Two quads and a triangle of a 2 x 1 grid with a triangle on top: points 0..6.
const char* const kVtuPoints = "0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0  1 2 0";
const std::vector<std::int64_t> kConnectivity = {0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 6};
const std::vector<std::int64_t> kOffsets = {4, 8, 11};
const std::vector<std::int64_t> kTypes = {9, 9, 5};

void expect_two_quads_and_a_triangle(const ReadMesh& m, const std::string& what) {
  ASSERT_EQ(m.points.size(), 7u) << what;
  EXPECT_EQ(m.quads, (std::vector<std::array<int, 4>>{{0, 1, 4, 3}, {1, 2, 5, 4}})) << what;
  EXPECT_EQ(m.triangles, (std::vector<std::array<int, 3>>{{3, 4, 6}})) << what;
  EXPECT_DOUBLE_EQ(m.points[6].x, 1.0) << what;
  EXPECT_DOUBLE_EQ(m.points[6].y, 2.0) << what;
}

// A little-endian array as VTK's binary data: a UInt32 byte count, then the values.
template <typename T>
std::string vtk_bytes(const std::vector<T>& values) {
  std::string data(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  const auto n = static_cast<std::uint32_t>(data.size());
  return std::string(reinterpret_cast<const char*>(&n), 4) + data;
}

std::string base64(const std::string& bytes) {
  char* text =
      CPLBase64Encode(static_cast<int>(bytes.size()), reinterpret_cast<const GByte*>(bytes.data()));
  std::string out = text;
  CPLFree(text);
  return out;
}

}  // namespace

// VTK's unstructured grids as ParaView, VTK and meshio write them: ascii arrays, appended
// raw and base64 data (UInt32 headers), each read to the same cells; a line cell skipped,
// a hexahedron refused; and the legacy ASCII file, before version 5 and after.
TEST(ReadMesh, VtkUnstructuredGridsInEveryEncoding) {
  TempDir dir;
  const std::string cells_ascii =
      "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 4 3 1 2 5 4 3 4 6"
      "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8 11"
      "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">9 9 5</DataArray>";
  auto vtu = [](const std::string& points, const std::string& cells, const std::string& tail) {
    return std::string(
               "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
               "version=\"1.0\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>"
               "<Piece NumberOfPoints=\"7\" NumberOfCells=\"3\"><Points>") +
           points + "</Points><Cells>" + cells + "</Cells></Piece></UnstructuredGrid>" + tail +
           "</VTKFile>\n";
  };
  write_file(dir.file("ascii.vtu"),
             vtu(std::string("<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                             "format=\"ascii\">") +
                     kVtuPoints + "</DataArray>",
                 cells_ascii, ""));
  expect_two_quads_and_a_triangle(read_mesh(dir.file("ascii.vtu")), "ascii");
  // Appended: the points as Float32, the cells as Int64 and UInt8, one after the other.
  std::vector<float> xyz;
  std::istringstream in(kVtuPoints);
  for (float v; in >> v;) xyz.push_back(v);
  const std::vector<std::uint8_t> types(kTypes.begin(), kTypes.end());
  const std::vector<std::string> arrays = {vtk_bytes(xyz), vtk_bytes(kConnectivity),
                                           vtk_bytes(kOffsets), vtk_bytes(types)};
  for (const bool raw : {true, false}) {
    std::vector<std::size_t> offset;
    std::string data;
    for (const std::string& a : arrays) {
      offset.push_back(data.size());
      data += raw ? a : base64(a);
    }
    auto appended = [&](const char* type, const char* name, int k, const char* extra) {
      return std::string("<DataArray type=\"") + type + "\" Name=\"" + name + "\" " + extra +
             "format=\"appended\" offset=\"" + std::to_string(offset[k]) + "\"/>";
    };
    const std::string file = dir.file(raw ? "raw.vtu" : "base64.vtu");
    write_file(file,
               vtu(appended("Float32", "Points", 0, "NumberOfComponents=\"3\" "),
                   appended("Int64", "connectivity", 1, "") + appended("Int64", "offsets", 2, "") +
                       appended("UInt8", "types", 3, ""),
                   std::string("<AppendedData encoding=\"") + (raw ? "raw" : "base64") + "\">\n_" +
                       data + "\n</AppendedData>"));
    expect_two_quads_and_a_triangle(read_mesh(file), raw ? "raw" : "base64");
  }
  // A line among the cells is skipped; a hexahedron refused.
  std::string with_line = cells_ascii;
  with_line.replace(with_line.find("3 4 6<"), 5, "3 4 6 0 3");
  with_line.replace(with_line.find("4 8 11<"), 6, "4 8 11 13");
  with_line.replace(with_line.find("9 9 5<"), 5, "9 9 5 3");
  std::string text = vtu(std::string("<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
                                     "format=\"ascii\">") +
                             kVtuPoints + "</DataArray>",
                         with_line, "");
  text.replace(text.find("NumberOfCells=\"3\""), 17, "NumberOfCells=\"4\"");
  write_file(dir.file("line.vtu"), text);
  const ReadMesh lined = read_mesh(dir.file("line.vtu"));
  expect_two_quads_and_a_triangle(lined, "line");
  EXPECT_EQ(lined.num_skipped_elements, 1u);
  std::string hex = text;
  hex.replace(hex.find("9 9 5 3<"), 7, "9 9 5 12");
  EXPECT_NE(read_error(dir, "hex.vtu", hex).find("cell 3 is of VTK type 12"), std::string::npos);
  // Legacy, version 4.2 and 5.1.
  const std::string head =
      "# vtk DataFile Version 4.2\nmesh\nASCII\nDATASET UNSTRUCTURED_GRID\n"
      "POINTS 7 double\n" +
      std::string(kVtuPoints) + "\n";
  write_file(dir.file("v42.vtk"), head +
                                      "CELLS 3 14\n4 0 1 4 3\n4 1 2 5 4\n3 3 4 6\n"
                                      "CELL_TYPES 3\n9\n9\n5\nCELL_DATA 3\n");
  expect_two_quads_and_a_triangle(read_mesh(dir.file("v42.vtk")), "4.2");
  write_file(dir.file("v51.vtk"), head +
                                      "CELLS 4 11\nOFFSETS vtktypeint64\n0 4 8 11\n"
                                      "CONNECTIVITY vtktypeint64\n0 1 4 3 1 2 5 4 3 4 6\n"
                                      "CELL_TYPES 3\n9\n9\n5\n");
  expect_two_quads_and_a_triangle(read_mesh(dir.file("v51.vtk")), "5.1");
  EXPECT_NE(read_error(dir, "binary.vtk", "# vtk DataFile Version 4.2\nm\nBINARY\n")
                .find("only ASCII ones are read"),
            std::string::npos);
}
