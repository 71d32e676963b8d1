// What the mesh job writes from a MeshResult: every mesh file (with the boundary's kinds,
// the vertices' depths from a bathymetry raster and the quality summary), the plot and
// the JSON report, moved into place together only when all are complete.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/mesh_job.h"
#include "io/write_mesh.h"

namespace isoquad {

struct MeshJobOutputs {
  std::vector<MeshOutput> meshes;  // check_mesh_outputs() them before the meshing
  MeshWriteOptions write;
  // GDAL raster of depths (metres, positive down, any CRS): the vertices' depths, 0
  // where it has no value. Empty: none (unknown depths).
  std::string bathymetry_path;
  std::string plot_path;     // PNG: the mesh, or the tiling when it stopped early
  std::string report_path;   // JSON: mesh_report_json()
  bool overwrite = false;    // for the plot and the report (the meshes have their own)
  std::string command_line;  // in the GeoPackage's metadata and the report
};

struct MeshJobWritten {
  std::size_t num_open_edges = 0, num_land_edges = 0;  // extract_boundary()
  std::size_t num_without_depth = 0;  // vertices outside the bathymetry or on nodata
  std::vector<std::string> files;     // the mesh files written
};

// Writes them all or none (Error(output) when one cannot be written).
MeshJobWritten write_mesh_job_outputs(const MeshResult& result, const MeshJobOutputs& outputs);

// The quality summary as (name, value) pairs, as the GeoPackage's metadata keeps them.
std::vector<std::pair<std::string, std::string>> quality_items(const QualitySummary& q);

// Every vertex's depth from the raster (bilinear; 0 where it has no value) into
// `depth`. Returns the number of vertices without one.
std::size_t sample_depths(const std::string& path, const Domain& domain, const QuadMesh& mesh,
                          std::vector<double>& depth);

}  // namespace isoquad
