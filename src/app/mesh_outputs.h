// What the mesh job writes from a MeshResult: every mesh file (with the boundary's kinds,
// the vertices' depths from a bathymetry raster and the quality summary), the plot and
// the JSON report, moved into place together only when all are complete.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/mesh_job.h"
#include "app/quad_zones.h"
#include "app/vertex_depths.h"
#include "io/write_mesh.h"

namespace isoquad {

// An output path that means stdout (--report -).
inline constexpr const char* kStdoutPath = "-";

struct MeshJobOutputs {
  std::vector<MeshOutput> meshes;  // check_mesh_outputs() them before the meshing
  MeshWriteOptions write;
  // GDAL rasters of depths or elevations (metres, any CRS), in priority order: the
  // vertices' depths (vertex_depths()). Empty: none (unknown depths).
  std::vector<DepthRaster> bathymetry;
  std::optional<double> min_depth_m;  // --min-depth: shallower depths are raised to it
  bool depth_average = false;         // --depth-average: vertex_depths(..., average)
  ZonesSource zones;                  // --zones: each quad's zone (quad_zones())
  double courant = 1.0;               // --courant: the time steps are at this Courant number
  double time_step_s = 0.0;           // --time-step: the quads' time steps are counted against it
  std::string plot_path;     // PNG: the mesh, or the tiling when it stopped early
  std::string report_path;   // JSON: mesh_report_json(); kStdoutPath: returned (::report)
  bool overwrite = false;    // for the plot and the report (the meshes have their own)
  std::string command_line;  // in the GeoPackage's metadata and the report
  // More rows of the GeoPackage's metadata (a region of --each: its attribute and value).
  std::vector<std::pair<std::string, std::string>> metadata;
};

struct MeshJobWritten {
  std::size_t num_open_edges = 0, num_land_edges = 0;  // extract_boundary()
  std::optional<VertexDepths> depths;  // with the bathymetry (the depths themselves moved out)
  std::optional<QuadZones> zones;      // with --zones (the quads' zones moved out)
  std::vector<std::string> files;     // the mesh files written
  std::string report;  // the JSON report when its path is kStdoutPath (printed once all is written)
  // Stage "output": the boundary's parts, the depths, zones, mesh files and plot (not the
  // report, which lists it).
  StageTime output_time;
};

// The quads' boundary, open where it lies on the front end's open boundary lines (the
// projected bbox or --clip, the lines of --open-boundary; within its tolerance, plus
// rounding), else land: for a mesh of `front`'s domain, made here or by another tool.
MeshBoundary boundary_of_domain(const QuadMesh& quads, const FrontEndResult& front);

// Writes them all or none (Error(output) when one cannot be written).
MeshJobWritten write_mesh_job_outputs(const MeshResult& result, const MeshJobOutputs& outputs);

// What a run warns of once its outputs are written, each a sentence without the
// "isoquad: warning: " before it: vertices outside the bathymetry; a mesh mostly dry
// (elevations given as depths, or the reverse); --embed's lines mostly not followed;
// a D-Flow FM net file or a SCHISM grid with what their checks refuse.
// `max_orthogonality`: SmoothParams::max_orthogonality of the run (0: off).
std::vector<std::string> mesh_job_warnings(const MeshResult& result, const MeshJobOutputs& outputs,
                                           const MeshJobWritten& written, double max_orthogonality);

// The summary's lines that follow the mesh's (format_mesh_summary()): the files written
// and the boundary's edges (when the run made quads), the quads --schism-split cut, the
// depths and the time steps.
std::string format_written_summary(const MeshResult& result, const MeshJobOutputs& outputs,
                                   const MeshJobWritten& written);

// The quality summary as (name, value) pairs, as the GeoPackage's metadata keeps them.
std::vector<std::pair<std::string, std::string>> quality_items(const QualitySummary& q);

}  // namespace isoquad
