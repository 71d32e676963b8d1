#include "app/mesh_outputs.h"

#include <algorithm>
#include <cmath>

#include "app/versions.h"
#include "core/geometry.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/crs.h"
#include "gis/raster_field.h"
#include "io/mesh_boundary.h"
#include "plot/plot_mesh.h"
#include "plot/plot_tiling.h"

namespace isoquad {

namespace {

std::string format_number(double v) { return printf_string("%.6g", v); }

}  // namespace

std::vector<std::pair<std::string, std::string>> quality_items(const QualitySummary& q) {
  return {{"num_quads", std::to_string(q.num_quads)},
          {"num_vertices", std::to_string(q.num_vertices)},
          {"num_nonconvex", std::to_string(q.num_nonconvex)},
          {"min_angle_deg", format_number(q.min_angle_deg)},
          {"max_angle_deg", format_number(q.max_angle_deg)},
          {"share_angles_75_105", format_number(q.share_angles_75_105)},
          {"size_ratio_median", format_number(q.size_ratio_median)},
          {"share_size_ratio_08_125", format_number(q.share_size_08_125)},
          {"orientation_mean_deg", format_number(q.orientation_mean_deg)},
          {"share_regular_interior", format_number(q.share_regular_interior)},
          {"eta_mean", format_number(q.eta_mean)},
          {"eta_min", format_number(q.eta_min)},
          {"schism_angle_ratio_violations", std::to_string(q.schism_angle_ratio_violations)},
          {"schism_aspect_ratio_violations", std::to_string(q.schism_aspect_violations)},
          {"schism_failures", std::to_string(q.schism_failures)},
          {"dflowfm_orthogonality_max", format_number(q.dflowfm_orthogonality_max)},
          {"dflowfm_orthogonality_violations", std::to_string(q.dflowfm_orthogonality_violations)},
          {"mesh_area_m2", format_number(q.mesh_area_m2)},
          {"domain_area_m2", format_number(q.domain_area_m2)},
          {"boundary_departure_max_m", format_number(q.boundary_departure_max_m)},
          {"boundary_departure_p95_h", format_number(q.boundary_departure_p95_h)}};
}

MeshBoundary boundary_of_domain(const QuadMesh& quads, const FrontEndResult& front) {
  return extract_boundary(
      quads, PolylineIndex(front.open_boundary_lines, front.open_boundary_slack_m),
      open_line_tolerance(front), front.open_boundary_chord_share, &front.open_boundary_line_group);
}

namespace {

MeshJobWritten write_outputs(const MeshResult& r, const MeshJobOutputs& o, OutputSet& set);

}  // namespace

MeshJobWritten write_mesh_job_outputs(const MeshResult& r, const MeshJobOutputs& o) {
  OutputSet set;
  try {
    return write_outputs(r, o, set);
  } catch (const Error& e) {
    throw set.explained(e);
  }
}

namespace {

MeshJobWritten write_outputs(const MeshResult& r, const MeshJobOutputs& o, OutputSet& set) {
  std::vector<StageTime> output_time;
  StageClock clock(output_time);
  MeshJobWritten written;
  MeshOutputData data;
  if (r.has_quads) {
    // The last guard of the all-quad guarantee: a vertex that is not finite (sizes gone
    // infinite) makes no quad, convex or not, and no file is written with one.
    for (std::size_t v = 0; v < r.quads.points.size(); ++v)
      if (!std::isfinite(r.quads.points[v].x) || !std::isfinite(r.quads.points[v].y))
        throw Error(ErrorClass::internal, "write",
                    "vertex " + std::to_string(v + 1) +
                        " of the mesh has no finite position; no mesh is written (please "
                        "report the input and options)");
    const FrontEndResult& front = r.fields.front;
    data.mesh = &r.quads;
    data.metrics = &r.metrics;
    data.crs_wkt = front.domain.crs_wkt;
    data.boundary = boundary_of_domain(r.quads, front);
    written.num_open_edges = data.boundary.num_open_edges;
    written.num_land_edges = data.boundary.num_land_edges;
    if (!o.bathymetry.empty()) {
      const RasterStack rasters(o.bathymetry, CrsInfo{front.domain.crs_wkt, front.domain.crs_name},
                                bounding_box(r.quads.points), r.fields.depths.get());
      written.depths = vertex_depths(rasters, r.quads, o.min_depth_m, o.depth_average);
      written.depths->kept = rasters.kept_text();
      written.depths->time_steps = courant_time_steps(r.quads, written.depths->depth, o.courant,
                                                      o.time_step_s, r.fields.scale.get());
      data.depth = std::move(written.depths->depth);
      data.time_step_s = std::move(written.depths->time_steps.per_quad_s);
    }
    if (o.zones.given()) {
      written.zones =
          quad_zones(o.zones, CrsInfo{front.domain.crs_wkt, front.domain.crs_name}, r.quads);
      data.zone = std::move(written.zones->zone);
    }
    if (!front.summary.embed_points_path.empty()) {
      data.vertex_point.assign(r.quads.points.size(), 0);
      if (!front.embed_point_name.empty()) data.vertex_point_name.assign(r.quads.points.size(), "");
      for (std::size_t k = 0; k < r.embedded_points.size(); ++k) {
        const int v = r.embedded_points[k].vertex;
        if (v < 0 || data.vertex_point[v] != 0) continue;  // the first point of a vertex
        data.vertex_point[v] = front.embed_point_number[k];
        if (!front.embed_point_name.empty()) data.vertex_point_name[v] = front.embed_point_name[k];
      }
    }
    for (const EmbeddedPath& path : r.embedded) {
      data.embedded.push_back(path.vertices);
      data.embedded_line.push_back(front.align_line_of[path.line]);  // the file's line
    }
    data.command_line = o.command_line;
    data.metadata = o.metadata;
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
  clock.lap("output");
  written.output_time = output_time.front();
  if (!o.report_path.empty()) {
    std::string json = mesh_report_json(r, o.command_line, r.has_quads ? &data.boundary : nullptr,
                                        written.depths ? &*written.depths : nullptr,
                                        written.zones ? &*written.zones : nullptr, output_time);
    if (o.report_path == kStdoutPath)
      written.report = std::move(json);
    else
      write_text_file(set.add(o.report_path, o.overwrite), json, true);
  }
  set.commit_all();
  return written;
}

}  // namespace

namespace {

// The first output in `format`, or null.
const MeshOutput* first_output(const MeshJobOutputs& outputs, MeshFormat format) {
  for (const MeshOutput& o : outputs.meshes)
    if (mesh_output_format(o) == format) return &o;
  return nullptr;
}

}  // namespace

// The share of the domain's area by which the mesh's may differ without a warning: the
// countries at 1:50m and 1:10m at their automatic sizes cover 99.80 to 100.01% of their
// domains, and 225 random regions at random sizes 99.2 to 100.03% (three islets under a
// few quads, 92 to 95%).
constexpr double kAreaWarningShare = 0.02;
// The median size ratio under which the quads are said to be smaller than asked: 0.61
// at the least over 620 meshes of countries and random regions other than an islet.
constexpr double kSmallQuadsRatio = 0.5;

std::vector<std::string> mesh_job_warnings(const MeshResult& r, const MeshJobOutputs& outputs,
                                           const MeshJobWritten& written,
                                           double max_orthogonality) {
  std::vector<std::string> warnings;
  if (written.zones && written.zones->counts.count(0)) {
    const std::size_t none = written.zones->counts.at(0), all = r.quads.quads.size();
    warnings.push_back(
        none == all
            ? printf_string("none of the %zu quads lies in a polygon of %s: every zone is 0 "
                            "(do its polygons cover this domain, in the CRS it names?)",
                            all, outputs.zones.path.c_str())
            : printf_string("%zu of the %zu quads lie in no polygon of %s: their zone is 0", none,
                            all, outputs.zones.path.c_str()));
  }
  const std::optional<VertexDepths>& depths = written.depths;
  if (depths && depths->num_filled)
    warnings.push_back(printf_string(
        "%zu vertices lie outside the bathymetry (or next to nodata): each took the depth of "
        "the nearest vertex with one, up to %.0f m away",
        depths->num_filled, depths->max_fill_distance_m));
  // Most of the mesh above the water: likely elevations given as depths, or the reverse.
  if (depths && depths->num_dry > 0.9 * static_cast<double>(r.quads.points.size()))
    warnings.push_back(printf_string(
        "%zu of the mesh's %zu vertices are dry (depth 0 or less): a raster of elevations "
        "(positive up, as GEBCO's) is given with --elevation, one of depths (positive down) "
        "with --bathymetry",
        depths->num_dry, r.quads.points.size()));
  // A DEM as INPUT gives the domain, not the depths: a model grid written without them
  // is flat.
  const auto& raster_input = r.fields.front.summary.raster;
  if (raster_input && outputs.bathymetry.empty())
    for (MeshFormat f : {MeshFormat::gr3, MeshFormat::fort14, MeshFormat::sms2dm, MeshFormat::mike,
                         MeshFormat::slf, MeshFormat::nc})
      if (const MeshOutput* o = first_output(outputs, f)) {
        warnings.push_back(
            o->path + ": no depths (the DEM INPUT bounds the domain; give it as --elevation '" +
            r.fields.front.summary.input_path +
            "' too, or as --bathymetry when its values are depths, positive down, for its "
            "depths at the vertices)");
        break;
      }
  // --embed on lines the rows of quads cannot follow (winding or bending within a few
  // quads): say so, with what helps.
  const EmbedStats& e = r.embed;
  if (e.line_length_m > 0 && e.covered_length_m < 0.5 * e.line_length_m)
    warnings.push_back(printf_string(
        "--embed: edges on the lines span only %.0f%% of their %.1f km inside the domain: "
        "lines that wind or bend within a few quads cannot be followed; simplify them, or "
        "refine round them (--refine with --refine-width-field)",
        100 * e.covered_length_m / e.line_length_m, e.line_length_m / 1000));
  const QualitySummary& q = r.quality;
  // Quads as large as parts of the domain (an island, a peninsula a quad or two across)
  // cut across them: the mesh's area strays from the domain's (on real coasts at their
  // sizes, within 1%).
  if (q.domain_area_m2 > 0 &&
      std::abs(q.mesh_area_m2 - q.domain_area_m2) > kAreaWarningShare * q.domain_area_m2)
    warnings.push_back(printf_string(
        "the mesh covers %.1f%% of the domain's area: its quads are too large for parts of "
        "it, which they cut across (the coast lies up to %.0f m, %.2f h, off the mesh's "
        "boundary, near %s); a smaller --size or --hmax, or --refine there, follows the coast",
        100 * q.mesh_area_m2 / q.domain_area_m2, q.boundary_departure_max_m,
        q.boundary_departure_max_h,
        format_meshing_place(q.boundary_departure_where, r.fields.front.domain.crs_wkt).c_str()));
  // A domain smaller than the quads asked for (an islet at a country's sizes): its few
  // quads are far smaller than the field says, which the size line shows unexplained.
  if (q.size_ratio_median > 0 && q.size_ratio_median < kSmallQuadsRatio)
    warnings.push_back(printf_string(
        "the quads are %.2g of the sizes asked (median sqrt(area)/h): the domain, %.4g km2 in "
        "%zu quads, is too small for quads of those sizes; smaller sizes (--hmax, --size) "
        "give quads of the size asked",
        q.size_ratio_median, q.domain_area_m2 / 1e6, r.quads.quads.size()));
  // A D-Flow FM network that D-Flow FM would refuse as it is.
  if (const MeshOutput* nc = first_output(outputs, MeshFormat::nc);
      nc && q.dflowfm_orthogonality_violations > 0)
    warnings.push_back(printf_string(
        "%s: %zu links between quads have an orthogonality over 0.5 (up to %.3f): D-Flow FM "
        "stops on it (\"network is not orthogonal\") unless CosPhiuTrsh in the .mdu's "
        "[geometry] is raised above that%s",
        nc->path.c_str(), q.dflowfm_orthogonality_violations, q.dflowfm_orthogonality_max,
        max_orthogonality > 0 ? " (these are where moving the quads' interior corners did not "
                                "lower it: quads that meet at a reflex corner of the coast)"
                              : "; --max-orthogonality 0.45 moves vertices to lower them"));
  // A SCHISM grid with quads its manual asks to be split.
  if (const MeshOutput* gr3 = first_output(outputs, MeshFormat::gr3);
      gr3 && q.schism_failures > 0 && !outputs.write.schism_split)
    warnings.push_back(printf_string(
        "%s: %zu quads fail SCHISM's checks (%zu with the smallest angle under half the "
        "largest, %zu with the longest side over 5 times the shortest), which SCHISM's manual "
        "asks to be split into triangles (its fix_bad_quads): --schism-split writes them so",
        gr3->path.c_str(), q.schism_failures, q.schism_angle_ratio_violations,
        q.schism_aspect_violations));
  return warnings;
}

std::string format_written_summary(const MeshResult& r, const MeshJobOutputs& outputs,
                                   const MeshJobWritten& written) {
  std::string text;
  if (r.has_quads) {
    text += "output:      ";
    for (const std::string& file : written.files) text += " " + file;
    text += "\nboundary:     " + std::to_string(written.num_open_edges) + " open edges, " +
            std::to_string(written.num_land_edges) + " land edges\n";
    for (const MeshOutput& o : outputs.meshes)
      if (outputs.write.schism_split && mesh_output_format(o) == MeshFormat::gr3)
        text += printf_string(
            "SCHISM split: %zu quads failing its checks written as two triangles each in %s\n",
            r.quality.schism_failures, o.path.c_str());
  }
  if (const std::optional<QuadZones>& zones = written.zones) {
    text += printf_string("zones:        %zu polygon(s) of %s:", zones->num_polygons,
                          outputs.zones.path.c_str());
    for (const auto& [zone, count] : zones->counts)
      text += zone == 0 ? printf_string(" %zu quads in none;", count)
                        : printf_string(" %lld: %zu quads;", zone, count);
    text.back() = '\n';
  }
  if (const std::optional<VertexDepths>& depths = written.depths) {
    text += printf_string("depths:       %.6g .. %.6g m", depths->min_m, depths->max_m);
    if (depths->averaged) text += " (each a mean over a square as wide as the vertex's quads)";
    if (!depths->kept.empty()) text += " (from " + depths->kept + ")";
    if (depths->num_raised)
      text += printf_string(", %zu vertices raised to --min-depth", depths->num_raised);
    text += "\n";
    const TimeSteps& t = depths->time_steps;
    if (t.limiting_quad >= 0) {
      const Point2 c = quad_centroid(r.quads, t.limiting_quad);
      text += printf_string(
          "time step:    %.3g s at a gravity-wave Courant number of %.3g, set by a quad %.0f m "
          "wide in %.0f m of water at (%.1f, %.1f); median quad %.3g s",
          t.min_s, t.courant, t.width_m, t.depth_m, c.x, c.y, t.median_s);
      if (outputs.time_step_s > 0)
        text += printf_string("; %zu of %zu wet quads under --time-step %.6g s", t.num_under_target,
                              t.num_wet, outputs.time_step_s);
      text += "\n";
    }
  }
  return text;
}

}  // namespace isoquad
