// Reading meshes that other tools wrote (and isoquad's own outputs), to measure them:
// SCHISM's .gr3/.ll, ADCIRC's .14, SMS's .2dm, Gmsh's .msh (ASCII 2.2 and 4.1), MIKE
// 21/3 FM's .mesh, UGRID netCDF (.nc, also D-Flow FM's older net files), TELEMAC's
// Selafin (.slf), VTK's .vtu and .vtk, and layers of polygons (isoquad's GeoPackage, or elements
// exported as polygons). Only the nodes and the 2D elements are read: triangles and quadrangles.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad {

struct ReadMesh {
  std::string format;  // "gr3", "14", "2dm", "msh", "mesh", "nc", "slf", "vtu", "vtk", "polygons"
  std::vector<Point2> points;             // as in the file
  std::vector<std::array<int, 4>> quads;  // 0-based indices into points, as in the file
  std::vector<std::array<int, 3>> triangles;
  // The file's own numbers of its nodes and elements where it numbers them (.gr3, .ll,
  // .14, .2dm, .msh, MIKE's .mesh), in the order of points, quads and triangles; empty
  // where it does not (the others: numbered from 1 in order, file_number). The messages
  // and `quality -o`'s ids say these, as the tool that wrote the file shows them.
  std::vector<long long> point_ids, quad_ids, triangle_ids;
  // The file's CRS, when the format holds one (MIKE's projection: "EPSG:4326" for its
  // LONG/LAT, else its WKT; UGRID's grid mapping: its WKT or EPSG code, or EPSG:4326 for
  // longitudes; a layer's CRS; EPSG:4326 for SCHISM's .ll; the one isoquad names in a
  // .gr3's or .14's title line, "... CRS: EPSG:32630" or a PROJ string); empty otherwise.
  std::string crs;
  std::size_t num_skipped_elements = 0;  // lines and points of a .msh
  // Each node's depth or bed level where the format has one (.gr3, .ll, .14: the depth;
  // .2dm, .mesh: z; .nc: the nodes' bed level (*_node_z, NetNode_z); .slf: BOTTOM at the
  // first time step), in the order of points; empty for the other formats (.msh, a layer
  // of polygons), or when a node lacks it.
  std::vector<double> node_values;
  // A .gr3's (.ll's, .14's) open boundaries, a MIKE .mesh's (its nodes' codes) or a
  // TELEMAC .slf's (the .cli beside it): each its nodes in order (indices into points);
  // empty for the other formats, and for a file without them.
  std::vector<std::vector<int>> open_boundaries;
  // Of those, a .14's (or .gr3's) flux boundaries (ADCIRC's IBTYPE 2, 12, 22, 32, 52: a
  // river's inflow), listed among its land boundaries and read as open, after the open
  // ones.
  std::size_t num_flux_boundaries = 0;
  // What the reader left out, for warnings (a .gr3's land section it could not read).
  std::vector<std::string> notes;
  // Named lines of the boundary: a Gmsh .msh's physical groups of curves (each its tag,
  // its name from $PhysicalNames or empty, and its line elements) or an SMS .2dm's
  // nodestrings (each its number in the file from 1, the name after its last node or
  // empty, and its edges), as node pairs (indices into points), in the order of the
  // tags; empty for the other formats.
  struct CurveGroup {
    long long tag = 0;
    std::string name;
    std::vector<std::array<int, 2>> edges;
  };
  std::vector<CurveGroup> curve_groups;
};

// The file's number of its k-th node or element (`ids`: ReadMesh::point_ids, quad_ids or
// triangle_ids): ids[k], or k + 1 when the file numbers none.
inline long long file_number(const std::vector<long long>& ids, std::size_t k) {
  return ids.empty() ? static_cast<long long>(k) + 1 : ids[k];
}

// The format from the file's extension (.gr3, .ll, .14 (also fort.14 and .grd), .2dm,
// .msh, .mesh, .nc, .slf or .srf, and .gpkg, .shp or .geojson for polygons); Error(usage)
// for any other.
std::string mesh_file_format(const std::string& path);

// Whether the path names a mesh file of one of read_mesh's formats but the layers of
// polygons (.gpkg, .shp, .geojson), which are read as vector data elsewhere: a mesh
// given where a domain is wanted is read with read_mesh and its outline taken. A netCDF
// file is one when it holds a mesh (UGRID, a D-Flow FM net file), else a raster grid.
bool is_mesh_file(const std::string& path);

// Reads the mesh. Error(input) naming the file and the line for what it cannot read:
// a missing or malformed line, an element with a node that is not in the file, an
// element of another kind than a triangle or a quadrangle (second-order elements), a
// binary .msh.
ReadMesh read_mesh(const std::string& path);

// Sets the open boundaries of a .msh or a .2dm from its named lines (curve_groups): the
// runs of the outline along the lines of the groups given, by name or by number (each
// run within one group); none given: the groups whose name begins with "open" (any
// case: isoquad's "open" and "open_1"..., "OpenBoundary"), as read_mesh does.
// Error(usage) for a group the file does not have (naming those it has), for a group
// given none of whose lines lies on the outline, and for a mesh of another format.
void open_boundaries_from_groups(ReadMesh& mesh, const std::vector<std::string>& groups,
                                 const std::string& path);

// What the format calls its groups: "physical group(s) of curves" (.msh),
// "nodestring(s)" (.2dm).
std::string curve_groups_kind(const ReadMesh& mesh, bool plural);

// The groups for a message: `7, 8 "land"` (the first ten, then the count); empty when
// none.
std::string curve_groups_text(const ReadMesh& mesh);

}  // namespace isoquad
