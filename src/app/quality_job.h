// `isoquad quality`: a mesh that another tool made (Gmsh, SMS, OceanMesh2D...) or an
// earlier run, measured as `isoquad mesh` measures its own: against the sizing and cross
// fields that the same domain and options give, with the same report.
#pragma once

#include <string>
#include <vector>

#include "app/fields_job.h"
#include "gis/read_mesh.h"
#include "quad/quad_mesh.h"
#include "quad/quad_quality.h"

namespace isoquad {

struct QualityJobOptions {
  // The domain, its sizes and its cross field; without a path to read (fields.front.read
  // .path empty), the domain is the mesh's own outline (mesh_outline), read in the mesh's
  // CRS, which must then be known (mesh_crs or the file's).
  FieldsOptions fields;
  std::string mesh_path;  // the mesh to measure (read_mesh's formats)
  // The mesh's CRS (anything parse_crs reads); empty: the file's own when its format
  // has one (a MIKE .mesh, a UGRID .nc), else the meshing CRS (the mesh and the domain
  // projected alike).
  std::string mesh_crs;
};

struct QualityJobResult {
  FieldsResult fields;
  std::string format;        // the file's (read_mesh)
  std::string mesh_crs;      // what the mesh's coordinates were read in, for the summary
  bool transformed = false;  // the points were transformed into the meshing CRS
  bool reversed = false;     // the file's elements were clockwise: measured reversed
  QuadMesh quads;            // in the meshing CRS, with the boundary vertices on the chains
  // The file's numbers of its nodes and quads (ReadMesh::point_ids, quad_ids; empty: from
  // 1 in order), for -o's ids.
  std::vector<long long> point_ids, quad_ids;
  QualitySummary quality;    // of the quads; D-Flow FM's links and the areas of every cell
  QuadMetrics metrics;
  std::size_t num_triangles = 0;
  std::size_t num_inverted_triangles = 0;  // clockwise (or flat) after the file's orientation
  double triangle_min_angle_deg = 0, triangle_max_angle_deg = 0;
  // The side of the equilateral triangle of a triangle's area over h at its centroid.
  double triangle_size_ratio_median = 0, triangle_share_size_08_125 = 0;
  // With triangles: the interior vertices whose elements' ideal angles (60 degrees a
  // triangle's, 90 a quad's) make 360 (six triangles alone; or four quads, or three
  // triangles and two quads, in a mesh of both).
  double triangle_share_regular_interior = 0;
  std::size_t num_skipped_elements = 0;  // lines and points of a .msh
  // Without INPUT (an empty read path): the loops of the mesh's outline, its domain.
  std::size_t num_outline_loops = 0;
  // Boundary vertices of the mesh (on sides of one element) on the domain's boundary (within
  // `on_boundary_tolerance_m`), and how far the others lie from it (searched up to
  // `off_boundary_search_m`; those farther counted in num_boundary_far).
  std::size_t num_boundary_on = 0, num_boundary_off = 0, num_boundary_far = 0;
  // False when a mesh with triangles has no outline (mesh_outline refused it): then
  // neither the boundary vertices nor the coast's departure are measured.
  bool coast_measured = true;
  double on_boundary_tolerance_m = 0, off_boundary_search_m = 0, boundary_off_max_m = 0;
  // Quads whose centroid lies outside the domain (no size or cross there: their size
  // ratio and orientation count as 0).
  std::size_t num_quads_outside = 0;
  std::vector<std::string> warnings;
};

// Reads the mesh, builds the domain and its fields, and measures the mesh. Error(input)
// for a mesh that cannot be read or that lies wholly off the domain (another CRS: give
// mesh_crs); Error(crs) for a CRS that cannot be read or used.
QualityJobResult measure_mesh_file(const QualityJobOptions& options,
                                   const Progress& progress = Progress());

std::string format_quality_job_summary(const QualityJobResult& r);
// `isoquad quality --report`: the version and command line, "mesh" (the file, its
// format and counts), "domain", "sizing", "quality" (as the mesh report's) and "stages".
std::string quality_job_report_json(const QualityJobResult& r, const std::string& command_line);

}  // namespace isoquad
