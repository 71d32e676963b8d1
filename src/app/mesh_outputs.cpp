#include "app/mesh_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/versions.h"
#include "gis/atomic_output.h"
#include "gis/raster_field.h"
#include "io/mesh_boundary.h"
#include "plot/plot_mesh.h"
#include "plot/plot_tiling.h"

namespace isoquad {

namespace {

std::string format_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> quality_items(const QualitySummary& q) {
  return {{"num_quads", std::to_string(q.num_quads)},
          {"num_vertices", std::to_string(q.num_vertices)},
          {"num_nonconvex", std::to_string(q.num_nonconvex)},
          {"min_angle_deg", format_number(q.min_angle_deg)},
          {"max_angle_deg", format_number(q.max_angle_deg)},
          {"share_angles_75_105", format_number(q.share_angles_75_105)},
          {"size_ratio_median", format_number(q.size_ratio_median)},
          {"share_size_08_125", format_number(q.share_size_08_125)},
          {"orientation_mean_deg", format_number(q.orientation_mean_deg)},
          {"share_regular_interior", format_number(q.share_regular_interior)},
          {"eta_mean", format_number(q.eta_mean)},
          {"eta_min", format_number(q.eta_min)},
          {"schism_angle_ratio_violations", std::to_string(q.schism_angle_ratio_violations)},
          {"schism_aspect_violations", std::to_string(q.schism_aspect_violations)},
          {"schism_failures", std::to_string(q.schism_failures)},
          {"dflowfm_orthogonality_max", format_number(q.dflowfm_orthogonality_max)},
          {"dflowfm_orthogonality_violations", std::to_string(q.dflowfm_orthogonality_violations)},
          {"mesh_area_m2", format_number(q.mesh_area_m2)},
          {"domain_area_m2", format_number(q.domain_area_m2)},
          {"boundary_departure_max_m", format_number(q.boundary_departure_max_m)},
          {"boundary_departure_p95_h", format_number(q.boundary_departure_p95_h)}};
}

MeshJobWritten write_mesh_job_outputs(const MeshResult& r, const MeshJobOutputs& o) {
  OutputSet set;
  MeshJobWritten written;
  MeshOutputData data;
  if (r.has_quads) {
    const FrontEndResult& front = r.fields.front;
    data.mesh = &r.quads;
    data.metrics = &r.metrics;
    data.crs_wkt = front.domain.crs_wkt;
    // Boundary parts on the open boundary's lines (the projected bbox, or the lines of
    // --open-boundary; within the front end's tolerance, plus rounding) are open.
    double extent = 0.0;
    for (const auto& line : front.open_boundary_lines)
      for (const Point2& p : line) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    data.boundary = extract_boundary(
        r.quads, PolylineIndex(front.open_boundary_lines, front.open_boundary_slack_m),
        front.open_boundary_tolerance_m + 1e-7 * extent, front.open_boundary_chord_share);
    written.num_open_edges = data.boundary.num_open_edges;
    written.num_land_edges = data.boundary.num_land_edges;
    if (!o.bathymetry.empty()) {
      const RasterStack rasters(o.bathymetry, CrsInfo{front.domain.crs_wkt, front.domain.crs_name},
                                bounding_box(r.quads.points));
      written.depths = vertex_depths(rasters, r.quads, o.min_depth_m);
      written.depths->time_steps =
          courant_time_steps(r.quads, written.depths->depth, o.courant, o.time_step_s);
      data.depth = std::move(written.depths->depth);
      data.time_step_s = std::move(written.depths->time_steps.per_quad_s);
    }
    for (const EmbeddedPath& path : r.embedded) {
      data.embedded.push_back(path.vertices);
      data.embedded_line.push_back(front.align_line_of[path.line]);  // the file's line
    }
    data.command_line = o.command_line;
    data.libraries = library_versions_line();
    data.quality = quality_items(r.quality);
    written.files = write_mesh_outputs(data, o.meshes, o.write, set);
  }
  if (!o.plot_path.empty()) {
    if (r.has_quads) {
      PlotMeshParams pp;
      pp.path = set.add(o.plot_path, o.overwrite);
      pp.overwrite = true;
      if (r.fields.num_aligned_vertices > 0) pp.lines = r.fields.front.align_lines;
      for (const EmbeddedPath& path : r.embedded) {
        pp.embedded.emplace_back();
        for (int v : path.vertices) pp.embedded.back().push_back(r.quads.points[v]);
      }
      plot_mesh(r.quads, r.metrics, r.quality, pp);
    } else {
      PlotTilingParams pp;
      pp.path = set.add(o.plot_path, o.overwrite);
      pp.overwrite = true;
      plot_tiling(r.fields.mesh, r.tiling.tiling, r.tiling.graph, pp);
    }
  }
  if (!o.report_path.empty()) {
    std::string json = mesh_report_json(r, o.command_line, r.has_quads ? &data.boundary : nullptr,
                                        written.depths ? &*written.depths : nullptr);
    if (o.report_path == kStdoutPath)
      written.report = std::move(json);
    else
      write_text_file(set.add(o.report_path, o.overwrite), json, true);
  }
  set.commit_all();
  return written;
}

}  // namespace isoquad
