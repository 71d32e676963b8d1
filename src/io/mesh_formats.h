// The format writers behind write_mesh_outputs (internal to src/io). Each writes to the
// temporary path it is given; the caller moves it into place.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/write_mesh.h"

namespace isoquad {

// The mesh with its coordinates in the output CRS.
struct MeshView {
  const MeshOutputData* data = nullptr;
  std::vector<Point2> points;  // #P output coordinates
  std::string crs_wkt;
  bool geographic = false;     // lon/lat degrees
};

// The per-quad values the formats with cell data write (GeoPackage, GeoJSON, FlatGeobuf,
// VTU, VTK, UGRID), in this order: the metrics, then time_step_s (NaN where dry) and
// zone when known. `integer`: whole numbers (the zone).
struct QuadField {
  const char* name;
  const std::vector<double>* values;  // #Q
  const char* units;                  // UDUNITS, for UGRID
  bool integer = false;
};
std::vector<QuadField> quad_fields(const MeshOutputData& data);

// The `what` path is the final name, for messages.
// `open_per_segment`: each open segment its own physical group (MeshWriteOptions).
void write_msh_file(const MeshView& v, const std::string& path, const std::string& what,
                    const std::string& version, bool open_per_segment);
// `points`: the mesh's or their lon/lat (EPSG:4326, hgrid.ll). `schism_split`: the quads
// that fail SCHISM's checks as two triangles each (MeshWriteOptions).
// SCHISM's element property file (.prop) of hgrid.gr3's elements: "element zone" lines,
// the two triangles of a quad split as hgrid.gr3 splits it both with its zone.
void write_prop_file(const MeshView& v, const std::string& path, const std::string& what,
                     bool schism_split);
void write_gr3_file(const MeshView& v, const std::vector<Point2>& points, const std::string& path,
                    const std::string& what, bool schism_split);
void write_vtk_legacy_file(const MeshView& v, const std::string& path, const std::string& what);
void write_ugrid_file(const MeshView& v, const std::string& path, const std::string& what);
void write_2dm_file(const MeshView& v, const std::string& path, const std::string& what);
// DHI MIKE 21/3 FM: the quads, the bed level and the boundary codes (land 1, each open
// segment its own from 2).
void write_mike_mesh_file(const MeshView& v, const std::string& path, const std::string& what);
// TELEMAC-2D: the geometry (the quads cut into triangles) and its boundary conditions.
void write_telemac_files(const MeshView& v, const std::string& path, const std::string& what,
                         const std::string& cli_path, const std::string& cli_what);
// ADCIRC: the grid (the quads cut into triangles) and its boundaries.
void write_fort14_file(const MeshView& v, const std::string& path, const std::string& what);
// Quad q as two counter-clockwise triangles across the diagonal whose triangles'
// skewnesses (SCHISM's: the longest side over the radius of the circle of the same area)
// add up to less, as SCHISM's fix_bad_quads chooses (in the meshing CRS, as meshed; the
// diagonal from corner 0 when both are as good). Every quad so, in order, for the formats
// of triangle-only models.
std::array<std::array<int, 3>, 2> quad_as_triangles(const QuadMesh& mesh, int q);
std::vector<std::array<int, 3>> quads_as_triangles(const QuadMesh& mesh);

// The title line's note of the coordinates' CRS in hgrid.gr3 and fort.14 (which SCHISM
// and ADCIRC skip, and isoquad reads back): " CRS: EPSG:n", or " CRS: " and the PROJ
// string of a CRS without a code; empty when the view has none.
std::string title_crs_note(const MeshView& v);

// Each node's zone from its quads' (--zones; TELEMAC's zones are the nodes'): the zone of
// most of them; on a tie a zone before none (0), then the smaller number.
std::vector<double> node_zones(const QuadMesh& mesh, const std::vector<double>& quad_zone);
// One open boundary segment as a D-Flow FM polyline, named after the stem of `what`.
void write_pli_file(const MeshView& v, const BoundarySegment& segment, const std::string& path,
                    const std::string& what);

}  // namespace isoquad
