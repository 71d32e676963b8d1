// Writers of the quad mesh, chosen by extension or by name (--output-format):
//   gpkg  GeoPackage: layers `quads` (per-quad metrics), `vertices` (degree, depth),
//         `boundary` (lines with kind open/land), `embedded` (--embed's paths of edges),
//         table `metadata`, QGIS styles in `layer_styles`;
//   vtu   VTK XML unstructured grid; vtk: legacy VTK (ASCII);
//   msh   Gmsh 4.1 ASCII (or 2.2), physical groups land (1), open (2), domain (3),
//         embedded (4, --embed's paths);
//   gr3   SCHISM hgrid.gr3 (quads, or with schism_split the quads that fail SCHISM's
//         checks as triangle pairs; depth positive down, open and land boundaries) and
//         its lon/lat companion (same name, extension .ll);
//   nc    UGRID-1.0 netCDF;
//   2dm   SMS generic 2D mesh (elevation z, boundary segments as nodestrings);
//   mesh  DHI MIKE 21/3 FM mesh (bed level z, boundary codes: land 1, open 2, 3...);
//   pli   D-Flow FM polylines of the open boundary: one file per open segment, the path
//         itself for one, else STEM_1.pli, STEM_2.pli... (Error(meshing) without any);
//   slf   TELEMAC-2D geometry (Selafin, the quads cut into triangles) and its boundary
//         conditions (same name, extension .cli);
//   geojson, fgb  the quads alone, as polygons with the per-quad metrics: GeoJSON in
//         longitudes and latitudes (RFC 7946) unless an output CRS is given, FlatGeobuf
//         in the mesh's CRS.
// Several outputs are written as one transaction (gis/atomic_output.h: OutputSet).
#pragma once

#include <string>
#include <vector>

#include "gis/atomic_output.h"
#include "io/mesh_boundary.h"
#include "quad/quad_mesh.h"
#include "quad/quad_quality.h"

namespace isoquad {

// Longitudes of a mesh that crosses the antimeridian (a quad spanning more than 180
// degrees of longitude) moved into [0, 360), so that its elements stay whole; unchanged
// otherwise, or when that does not help (a mesh round a pole). Returns whether it moved
// them.
bool unwrap_antimeridian(const QuadMesh& mesh, std::vector<Point2>& lonlat);

enum class MeshFormat {
  gpkg,
  vtu,
  vtk,
  msh,
  gr3,
  nc,
  sms2dm,
  mike,
  pli,
  slf,
  fort14,
  geojson,
  fgb
};

struct MeshOutput {
  std::string path;
  std::string format;  // gpkg, vtu, vtk, msh, gr3, nc, 2dm, mesh, pli, slf, 14, geojson,
                       // fgb; empty: by the path's extension
  bool overwrite = false;
  // With --zones: a .gr3 also writes its .prop (each SCHISM element's zone).
  bool zones = false;
};

// What is written besides the mesh itself.
struct MeshOutputData {
  const QuadMesh* mesh = nullptr;
  const QuadMetrics* metrics = nullptr;
  std::string crs_wkt;         // the mesh's (meshing) CRS
  MeshBoundary boundary;       // extract_boundary()
  std::vector<double> depth;   // #P metres, positive down; empty: unknown (written as 0)
  // #Q the time step at a gravity-wave Courant number of 1 (NaN: dry); empty: unknown.
  std::vector<double> time_step_s;
  // #Q each quad's zone (--zones; 0: in none); empty: none given.
  std::vector<double> zone;
  // #P with --embed-points: the number (from 1, in its file) of the point each vertex was
  // moved onto, 0 for none: the GeoPackage's vertices' `point`. Empty: none given.
  std::vector<int> vertex_point;
  // #P with named points (--embed-points-name, or their `name`): that point's name, the
  // vertices' `point_name`. Empty: no names.
  std::vector<std::string> vertex_point_name;
  // Paths of edges on lines (--embed; vertex ids), each with the index of its line in
  // the file: the GeoPackage's layer `embedded`.
  std::vector<std::vector<int>> embedded;
  std::vector<int> embedded_line;
  // #P and #Q the numbers the `id` columns give the vertices and quads (a measured
  // file's own: quality -o); empty: from 1 in order, as the model files number them.
  std::vector<long long> vertex_ids, quad_ids;
  // GeoPackage metadata.
  std::string command_line;
  std::vector<std::pair<std::string, std::string>> metadata;  // more rows, after the command line
  std::string libraries;  // "CGAL 5.5.1, Eigen 3.4.0, ..." (app/versions.h)
  std::vector<std::pair<std::string, std::string>> quality;  // name, value
};

struct MeshWriteOptions {
  std::string msh_version = "4.1";  // or "2.2"
  // Gmsh physical groups of the boundary: "kind" (land 1, open 2), or "segment" (land 1,
  // and each open segment its own, open_1, open_2... tagged 11, 12..., in hgrid.gr3's
  // order: a boundary condition per open boundary, as Thetis sets them).
  std::string msh_groups = "kind";
  // Writes coordinates in this CRS (anything parse_crs accepts); empty: the mesh's CRS.
  // Applies to every format but gr3, which is in the mesh's CRS (its .ll in lon/lat).
  std::string output_crs;
  // gr3 (and its .ll): each quad that fails SCHISM's checks (fails_schism_checks) written
  // as two triangles (quad_as_triangles), in its place, as SCHISM's manual asks
  // of a grid (its fix_bad_quads); false: every quad a quad.
  bool schism_split = false;
  std::string styles_dir;  // folder of the QGIS .qml styles embedded in GeoPackages
};

// The format of an output (Error(usage) for an unknown extension or format name).
MeshFormat mesh_output_format(const MeshOutput& output);
// Every file an output writes (gr3: also the .ll companion; slf: the .cli; pli: the
// path, as for one open segment).
std::vector<std::string> mesh_output_files(const MeshOutput& output);
// True when every file of the output exists (pli: the path, or the first of its numbered
// files, as for several open segments).
bool mesh_output_exists(const MeshOutput& output);
// Fails early (Error(usage) or Error(output)) for an unknown format or an output that
// cannot be written. Call before any long work.
void check_mesh_outputs(const std::vector<MeshOutput>& outputs, const MeshWriteOptions& options);
// Fails early for an extension write_mesh does not know.
void check_mesh_output_format(const std::string& path);

// Writes every output, all or none; returns the files written. Throws
// Error(usage|crs|output), or Error(meshing) for a .pli of a mesh without open boundary.
std::vector<std::string> write_mesh_outputs(const MeshOutputData& data,
                                            const std::vector<MeshOutput>& outputs,
                                            const MeshWriteOptions& options = MeshWriteOptions());
// The same, adding the outputs to `set`, whose commit_all() the caller calls (so that
// other outputs of the run, e.g. a plot or a report, join the same all-or-nothing set).
std::vector<std::string> write_mesh_outputs(const MeshOutputData& data,
                                            const std::vector<MeshOutput>& outputs,
                                            const MeshWriteOptions& options, OutputSet& set);

// One output, land boundary only, no depth (kept for simple callers).
void write_mesh(const QuadMesh& mesh, const QuadMetrics& metrics, const std::string& crs_wkt,
                const MeshOutput& output);

}  // namespace isoquad
