#include "app/mesh_job.h"

#include "app/quad_zones.h"
#include "app/vertex_depths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/quality_report.h"
#include "app/summary.h"
#include "core/error.h"
#include "core/json_writer.h"
#include "core/text.h"
#include "gis/crs.h"
#include "mesh/boundary_corners.h"
#include "mesh/locate.h"
#include "quad/quad_numbering.h"

namespace isoquad {

namespace {

// Where an attempt failed: the centroids of the quads left non-convex and the midpoints
// of crossing boundary edges.
std::vector<Point2> failure_points(const QuadMesh& m, const SmoothParams& params) {
  std::vector<Point2> points;
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
    if (quad_convexity(m, q) <= params.min_convexity) points.push_back(quad_centroid(m, q));
  for (const auto& c : boundary_crossings(m))
    points.push_back({0.5 * (m.points[c[0]].x + m.points[c[1]].x),
                      0.5 * (m.points[c[0]].y + m.points[c[1]].y)});
  return points;
}

}  // namespace

std::vector<LocalRefinement> refinements_at(const FieldsResult& f, const std::vector<Point2>& points,
                                            std::size_t max_places) {
  const TriangleLocator locator(f.mesh);
  std::vector<LocalRefinement> out;
  for (const Point2& p : points) {
    bool near = false;
    for (std::size_t i = 0; i < out.size() && !near; ++i)
      near = std::hypot(p.x - out[i].centre.x, p.y - out[i].centre.y) < 2 * out[i].radius_m;
    if (near) continue;
    const Location loc = locator.locate(p);
    if (loc.triangle < 0) continue;
    const double h = f.size.at(f.mesh, loc.triangle, loc.bary);
    out.push_back({p, h, 0.5 * h});
    if (out.size() > max_places) return {};
  }
  return out;
}

MeshResult build_mesh(const MeshOptions& options, const Progress& progress) {
  MeshResult r;
  // The shares of the progress line follow France at a uniform 3 km (fields 4.4 s,
  // tiling 8.8, smoothing 4.4): the fields 30%, the tiling 45%, the smoothing 20%.
  r.fields = build_fields(options.fields, progress.slice(0.0, 0.3));
  FieldsOptions fields = options.fields;  // with the local refinements of failed attempts

  // The tiling and quad stages, retried when smoothing cannot make every quad convex
  // or the mesh folds: such failures come from a few badly shaped tiles. The next
  // attempt has the sizes halved where this one failed (refinements_at), with the
  // background mesh and fields built again: a fold where a channel is narrower than the
  // quads comes back with any tiling of the same sizes. It keeps the tiling's variant, so
  // that the tiles change where the sizes did, not everywhere: a new variant would bring
  // its own failures elsewhere (the Norwegian and Barents seas at 1:10m failed at a new
  // place in each of four attempts, and met in the third with the variant kept). When
  // there is nothing to refine (failures at more than max_refined_places), the next
  // variant: variants 1 and 3 start from the other initialization (fronts or merging),
  // which moves every tile; variants 2 and 3 add a conforming iteration and leave pairs
  // of tiles as they are (no re-splitting: its tiles, cut along shortest paths, are the
  // likelier to be bent at a sharp reflex corner). The attempts are a fixed sequence, so
  // the output stays deterministic.
  int variant = 0;
  for (int attempt = 0;; ++attempt) {
    MeshOptions o = options;
    o.tiling.seed.lines = r.fields.front.align_lines;  // rows of tiles along --align's lines
    o.tiling.conform_iters += variant / 2;
    if (variant >= 2) o.tiling.resplit_rounds = 0;
    if (variant % 2 == 1)
      o.tiling.init = o.tiling.init == TilingInit::front ? TilingInit::merge : TilingInit::front;
    StageClock clock(r.fields.times);
    CornerParams corners;
    corners.corner_angle_deg = o.tiling.graph.corner_angle_deg;
    tag_corners(r.fields.mesh, r.fields.size, corners);  // the repairs may clear some
    r.attempts = attempt + 1;
    r.tiling_variants.push_back(variant);
    std::string problem;
    bool tiling_failed = false;
    std::vector<Point2> failed_at;
    try {
      r.tiling = build_tiling(r.fields.mesh, r.fields.size, r.fields.cross, o.tiling,
                              progress.slice(0.3, 0.75));
    } catch (const TilingError& e) {
      // A tile the repairs cannot mend (a sliver of water between a coast and the bbox
      // edge): retried like a fold, with smaller sizes there.
      if (!e.where() || options.max_attempts <= 1 || o.tiling.stop_after != TilingStep::none) throw;
      problem = e.message();
      tiling_failed = true;
      failed_at.push_back(*e.where());
    }
    clock.lap("tiling");
    if (o.tiling.stop_after != TilingStep::none) return r;

    if (problem.empty()) {
      progress.report("subdivide", 0.75);
      r.quads = subdivide_tiles(r.fields.mesh, r.tiling.tiling, r.tiling.graph, o.subdivide);
      clock.lap("subdivision");
      r.smooth = smooth_quads(r.fields.mesh, r.quads, o.smooth, &r.fields.size, &r.fields.cross,
                              progress.slice(0.76, 0.96));
      clock.lap("smoothing");
      if (r.smooth.num_nonconvex_after > 0) {
        std::string where;
        for (int q = 0; q < static_cast<int>(r.quads.quads.size()) && where.empty(); ++q)
          if (quad_convexity(r.quads, q) <= o.smooth.min_convexity)
            where = " (the first near " + format_point(r.quads.points[r.quads.quads[q][0]]) + ")";
        problem = std::to_string(r.smooth.num_nonconvex_after) +
                  " quad(s) could not be made strictly convex" + where;
      } else {
        Point2 at;
        const std::size_t crossings = count_boundary_crossings(r.quads, &at);
        if (crossings == 0) break;
        problem = "the mesh folds over itself: " + std::to_string(crossings) +
                  " pair(s) of boundary edges cross (the first near " + format_point(at) + ")";
      }
      failed_at = failure_points(r.quads, o.smooth);
    }
    if (attempt + 1 >= options.max_attempts) {
      // Where the earlier attempts failed too: a user can then look at every place.
      std::string earlier;
      for (std::size_t i = 0; i < r.retry_reasons.size(); ++i)
        earlier += "; attempt " + std::to_string(i + 1) + ": " + r.retry_reasons[i];
      // Where a piece narrower than --min-width was kept for the topology (a channel of
      // 1 m between two land polygons meshed at 70 m): the domain's, and the user's to
      // change.
      const DomainSummary& front = r.fields.front.summary;
      const double reach = 2 * front.target_size_m;
      for (const NarrowResult::Kept& kept : front.narrow.kept) {
        const Polygon& piece = kept.piece;
        Domain one;
        one.polygons.push_back(piece);
        const auto near = [&](const Point2& p) {
          return domain_contains(one, p) || distance_to_boundary(one, p) <= reach;
        };
        if (std::none_of(failed_at.begin(), failed_at.end(), near)) continue;
        const NarrowPlace place = place_of(piece);
        throw Error(ErrorClass::meshing, tiling_failed ? "tiling" : "smooth",
                    problem + " after " + std::to_string(r.attempts) +
                        " tiling attempt(s), next to a piece narrower than --min-width that "
                        "was kept since changing it would join or cut components or holes (near " +
                        format_meshing_place(place.at, r.fields.front.domain.crs_wkt) + ", about " +
                        printf_string("%.3g", place.width_m) +
                        " m across); no mesh is written: --hairline " +
                        printf_string("%.3g", 1.5 * place.width_m) +
                        " closes or cuts it, smaller sizes there (--refine, --hmin) resolve it" +
                        earlier);
      }
      if (tiling_failed)
        throw Error(ErrorClass::meshing, "tiling",
                    problem + " after " + std::to_string(r.attempts) +
                        " tiling attempt(s); no mesh is written (a piece of the domain narrower "
                        "than the quads, or a tile pinched between two coasts: a larger "
                        "--min-width fills or removes such pieces, a smaller --size or --hmin "
                        "resolves them)" +
                        earlier);
      // Fewer attempts than the default were asked for: more may mend it.
      const std::string more_attempts = options.max_attempts < MeshOptions{}.max_attempts
                                            ? "; more tiling attempts (--max-attempts, " +
                                                  std::to_string(MeshOptions{}.max_attempts) +
                                                  " by default) may mend it"
                                            : "";
      // Quads that fold where an inlet is narrower than they are: the domain's, and the
      // user's to change.
      if (r.smooth.num_nonconvex_after == 0)
        throw Error(ErrorClass::meshing, "smooth",
                    problem + " after " + std::to_string(r.attempts) +
                        " tiling attempt(s); no mesh is written (quads fold over each other "
                        "where an inlet or channel is narrower than they are: a larger "
                        "--min-width fills such inlets, a smaller --hmin or --size resolves "
                        "them" +
                        more_attempts + ")" + earlier);
      // A quad left non-convex: the smoothing's guarantee failed, isoquad's fault.
      throw Error(ErrorClass::internal, "smooth",
                  problem + " after " + std::to_string(r.attempts) +
                      " tiling attempt(s); no mesh is written (isoquad guarantees convex "
                      "quads: please report the input and options" +
                      more_attempts + ")" + earlier);
    }
    // The next attempt also has smaller sizes where this one failed.
    const std::vector<LocalRefinement> more =
        refinements_at(r.fields, failed_at, options.max_refined_places);
    if (!more.empty()) {
      fields.sizing.refinements.insert(fields.sizing.refinements.end(), more.begin(), more.end());
      r.refinements = fields.sizing.refinements;
      problem += "; sizes halved at " + std::to_string(more.size()) + " place(s) there";
      build_fields_on_domain(r.fields.front.domain, fields, r.fields, progress.slice(0.2, 0.3));
    } else {
      ++variant;
    }
    r.retry_reasons.push_back(problem);
    progress.report("retry: " + problem, 0.3);
  }
  StageClock clock(r.fields.times);
  const bool lines = options.embed_lines && !r.fields.front.align_lines.empty();
  if (lines || !r.fields.front.embed_points.empty()) {
    progress.report("embed", 0.96);
    EmbedParams embed = options.embed;
    embed.point_coast_m = r.fields.front.summary.simplify_m;
    r.embed = embed_lines(r.fields.mesh, r.quads,
                          lines ? r.fields.front.align_lines : std::vector<std::vector<Point2>>(),
                          embed, options.smooth, &r.fields.cross, &r.fields.size, &r.embedded,
                          r.fields.front.embed_points, &r.embedded_points);
    clock.lap("embedding");
  }
  if (options.renumber) {
    // Neighbours numbered close together, as models and their tools like (quad_numbering.h).
    const QuadNumbering numbering = reverse_cuthill_mckee(r.quads);
    std::vector<std::vector<int>*> lists;
    for (EmbeddedPath& path : r.embedded) lists.push_back(&path.vertices);
    renumber(r.quads, numbering, lists);
    for (EmbeddedPoint& p : r.embedded_points)
      if (p.vertex >= 0) p.vertex = numbering.new_vertex[p.vertex];
  }
  progress.report("quality", 0.97);
  r.quality = measure_quality(r.quads, r.fields.mesh, r.fields.size, r.fields.cross, &r.metrics);
  if (r.fields.num_aligned_vertices > 0)
    measure_line_following(r.quads, r.fields.front.align_lines, r.quality);
  clock.lap("quality");
  if (r.quality.num_nonconvex > 0)
    throw Error(ErrorClass::internal, "quality",
                std::to_string(r.quality.num_nonconvex) + " quad(s) are not strictly convex");
  if (r.quality.num_boundary_crossings > 0)
    throw Error(ErrorClass::internal, "quality",
                std::to_string(r.quality.num_boundary_crossings) +
                    " pair(s) of boundary edges cross: the mesh folds over itself");
  r.has_quads = true;
  progress.report("mesh", 1.0);
  return r;
}

std::string format_mesh_summary(const MeshResult& r) {
  std::ostringstream os;
  char buf[320];
  for (const TilingStepReport& s : r.tiling.steps) {
    std::snprintf(buf, sizeof buf, "tiling %-10s %d tiles, %.1f%% with 4 meta-vertices, %d irregular interior meta-vertices%s, %.3f s\n",
                  (s.step + ":").c_str(), s.stats.num_tiles, 100 * s.stats.share_quads,
                  s.stats.num_irregular_interior,
                  s.step == "butterfly"
                      ? (", " + std::to_string(s.butterflies_removed) + "/" +
                         std::to_string(s.butterflies_found) + " butterflies removed").c_str()
                  : s.step == "resplit"
                      ? (", " + std::to_string(s.pairs_resplit) + " pairs re-split").c_str()
                      : "",
                  s.seconds);
    os << buf;
  }
  for (std::size_t i = 0; i < r.retry_reasons.size(); ++i) {
    os << "retried:      tiling attempt " << i + 1 << " discarded: " << r.retry_reasons[i]
       << "\n";
  }
  if (!r.has_quads) return os.str();
  const QualitySummary& q = r.quality;
  std::snprintf(buf, sizeof buf, "quads:        %zu quads, %zu vertices, %zu non-convex\n", q.num_quads,
                q.num_vertices, q.num_nonconvex);
  os << buf;
  if (r.smooth.num_flips > 0 || r.smooth.num_collapses > 0) {
    std::snprintf(buf, sizeof buf,
                  "repaired:     %d quad edge flip(s), %d diagonal collapse(s) where smoothing "
                  "alone left a quad non-convex or the mesh folded\n",
                  r.smooth.num_flips, r.smooth.num_collapses);
    os << buf;
  }
  // A line with a count of repairs, when there were any (`format` takes the count).
  auto repairs_line = [&](int count, const char* format) {
    if (count <= 0) return;
    std::snprintf(buf, sizeof buf, format, count);
    os << buf;
  };
  repairs_line(r.smooth.num_sliver_collapses,
               "slivers:      %d flat quad(s) removed by diagonal collapses or thin rows merged\n");
  repairs_line(r.smooth.num_thin_repairs,
               "thin quads:   %d long and narrow quad(s) (SCHISM's aspect ratio) mended by "
               "diagonal collapses, flips or thin rows merged\n");
  repairs_line(r.smooth.num_corner_splits,
               "corners:      %d reflex corner(s) given a third quad where an interior vertex was "
               "glued to them\n");
  os << format_quad_shape_lines(q);
  if (r.fields.num_aligned_vertices > 0) os << format_align_line(q);
  if (!r.fields.front.summary.embed_points_path.empty() && r.fields.front.embed_points.empty()) {
    os << "points:       none of the file's points lies in or next to the domain\n";  // (--each)
  } else if (!r.fields.front.summary.embed_points_path.empty()) {
    const EmbedStats& e = r.embed;
    const FrontEndResult& front = r.fields.front;
    // The numbers (in the file) of the first points left off their vertex.
    std::string off;
    std::size_t num_off = 0, num_coast_on = 0;
    for (std::size_t k = 0; k < r.embedded_points.size(); ++k) {
      const EmbeddedPoint& p = r.embedded_points[k];
      if (p.vertex < 0) continue;
      if (distance(r.quads.points[p.vertex], p.target) <= EmbedParams().on_line_m) {
        num_coast_on += p.coast && p.shares < 0;
        continue;
      }
      if (++num_off <= 5) {
        off += (num_off > 1 ? ", " : "") + std::to_string(front.embed_point_number[k]);
        if (!front.embed_point_name.empty() && !front.embed_point_name[k].empty())
          off += " (" + front.embed_point_name[k] + ")";
      }
    }
    if (num_off > 5) off += "...";
    os << printf_string(
        "points:       %zu of the %zu points in or next to the domain on their vertex",
        e.num_points_on, front.embed_points.size());
    if (num_coast_on > 0)
      os << printf_string(" (%zu of them at the coast's point nearest them, up to %.3g m away)",
                          num_coast_on, e.max_coast_distance_m);
    if (e.num_points_shared > 0)
      os << printf_string(
          "; %zu %s the vertex of a point before %s within a fifth of a quad (%s)",
          e.num_points_shared, e.num_points_shared > 1 ? "share" : "shares",
          e.num_points_shared > 1 ? "them" : "it",
          e.max_shared_distance_m > 0
              ? printf_string("up to %.3g m away", e.max_shared_distance_m).c_str()
              : (e.num_points_shared > 1 ? "each at the same place" : "at the same place"));
    if (num_off > 0)
      os << printf_string(
          "; the others' vertices stop up to %.3g m short (%s %s: the quads between would leave "
          "[30, 150] degrees)",
          e.max_point_off_m, num_off > 1 ? "points" : "point", off.c_str());
    if (e.num_points_outside > 0)
      os << printf_string("; %zu outside the domain, not next to the coast, get none",
                          e.num_points_outside);
    os << "\n";
  }
  if (r.embed.requested && r.embed.line_length_m == 0) {
    os << "embedded:     no line lies farther than half a quad from the boundary (where the "
          "boundary's row of quads holds it)\n";
  } else if (r.embed.requested) {
    const EmbedStats& e = r.embed;
    const std::size_t interior = e.num_vertices - e.num_boundary;
    std::snprintf(
        buf, sizeof buf,
        "embedded:     %zu edges on %zu piece(s) of the lines inside the domain%s; %zu of "
        "their %zu interior vertices on the lines (farthest %.3g m off)%s\n",
        e.num_edges, e.num_runs,
        e.num_skipped
            ? (" (" + std::to_string(e.num_skipped) + " too short or with no path)").c_str()
            : "",
        e.num_on_line, interior, e.max_vertex_off_m,
        e.num_coast_ends ? (", " + std::to_string(e.num_coast_ends) +
                            " end(s) slid along the coast to where the lines meet it")
                               .c_str()
                         : "");
    os << buf;
    std::snprintf(buf, sizeof buf,
                  "              %.1f%% of the lines' %.1f km spanned by edges whose ends are on "
                  "them, the lines at most %.3g m off those edges\n",
                  e.line_length_m > 0 ? 100 * e.covered_length_m / e.line_length_m : 0.0,
                  e.line_length_m / 1000, e.max_chord_off_m);
    os << buf;
  }
  os << format_quad_connectivity_lines(q);
  return os.str();
}

std::string mesh_report_json(const MeshResult& r, const std::string& command_line,
                             const MeshBoundary* boundary, const VertexDepths* depths,
                             const QuadZones* zones, const std::vector<StageTime>& more_stages) {
  JsonWriter j;
  j.begin_object();
  add_report_header(j, command_line);
  j.begin_object("domain");
  add_domain_summary(j, r.fields.front.summary);
  j.end_object();
  j.begin_object("sizing");
  add_sizing_report(j, r.fields);
  j.begin_array("local_refinements");  // where failed tiling attempts halved the sizes
  for (const LocalRefinement& f : r.refinements)
    j.begin_object()
        .value("x_m", f.centre.x)
        .value("y_m", f.centre.y)
        .value("radius_m", f.radius_m)
        .value("size_m", f.size_m)
        .end_object();
  j.end_array();
  j.end_object();
  add_background_report(j, r.fields);
  j.begin_array("tiling");
  for (const TilingStepReport& s : r.tiling.steps) {
    j.begin_object()
        .value("step", s.step)
        .value("num_tiles", s.stats.num_tiles)
        .value("share_quads", s.stats.share_quads)
        .array("tile_num_meta_vertices_histogram", s.stats.tile_num_vertices_histogram)
        .array("interior_degree_histogram", s.stats.interior_degree_histogram)
        .value("num_degree3_pairs", s.stats.num_degree3_pairs)
        .value("num_irregular_interior", s.stats.num_irregular_interior)
        .value("iterations", s.iterations)
        .value("energy", s.energy)
        .value("butterflies_found", s.butterflies_found)
        .value("butterflies_removed", s.butterflies_removed)
        .value("pairs_resplit", s.pairs_resplit)
        .value("seconds", s.seconds)
        .end_object();
  }
  j.end_array();
  if (r.has_quads) {
    const QualitySummary& q = r.quality;
    j.begin_object("quality")
        .value("num_quads", q.num_quads)
        .value("num_vertices", q.num_vertices)
        .value("num_triangles", 0);
    add_quality_values(j, q);
    if (r.fields.num_aligned_vertices > 0) add_align_values(j, q);
    if (r.embed.requested)
      j.value("embed_num_runs", r.embed.num_runs)
          .value("embed_num_skipped", r.embed.num_skipped)
          .value("embed_num_edges", r.embed.num_edges)
          .value("embed_num_interior_vertices", r.embed.num_vertices - r.embed.num_boundary)
          .value("embed_num_on_line", r.embed.num_on_line)
          .value("embed_num_coast_ends", r.embed.num_coast_ends)
          .value("embed_max_vertex_off_m", r.embed.max_vertex_off_m)
          .value("embed_line_length_m", r.embed.line_length_m)
          .value("embed_covered_length_m", r.embed.covered_length_m)
          .value("embed_max_chord_off_m", r.embed.max_chord_off_m);
    if (!r.fields.front.summary.embed_points_path.empty())
      j.value("embed_points_read", r.fields.front.summary.embed_points_read)
          .value("embed_points_inside", r.fields.front.summary.embed_points_inside)
          .value("embed_points_with_vertex", r.embed.num_points)
          .value("embed_points_on_vertex", r.embed.num_points_on)
          .value("embed_points_max_off_m", r.embed.max_point_off_m)
          .value("embed_points_on_coast", r.embed.num_points_coast)
          .value("embed_points_coast_max_m", r.embed.max_coast_distance_m)
          .value("embed_points_shared", r.embed.num_points_shared)
          .value("embed_points_shared_max_m", r.embed.max_shared_distance_m);
    j.end_object();
    // Each point's node (from 1, as the mesh files number them: TELEMAC's LIST OF POINTS,
    // a station's node), how far it lies from the point, and why.
    if (!r.fields.front.summary.embed_points_path.empty()) {
      const FrontEndResult& front = r.fields.front;
      j.begin_array("embedded_points");
      for (std::size_t k = 0; k < r.embedded_points.size(); ++k) {
        const EmbeddedPoint& p = r.embedded_points[k];
        j.begin_object().value("point", front.embed_point_number[k]);
        if (!front.embed_point_name.empty()) j.value("name", front.embed_point_name[k]);
        j.value("node", p.vertex >= 0 ? static_cast<long long>(p.vertex) + 1 : 0LL);
        if (p.vertex >= 0) {
          j.value("distance_m", distance(r.quads.points[p.vertex], front.embed_points[k]))
              .value("coast", p.coast)
              .value("shares_point", p.shares >= 0 ? front.embed_point_number[p.shares] : 0);
        }
        j.end_object();
      }
      j.end_array();
    }
    if (boundary) {
      std::size_t open = 0, land = 0;
      for (const BoundarySegment& segment : boundary->segments)
        ++(segment.kind == BoundaryKind::open ? open : land);
      j.begin_object("boundary")
          .value("num_open_edges", boundary->num_open_edges)
          .value("num_land_edges", boundary->num_land_edges)
          .value("num_open_segments", open)
          .value("num_land_segments", land)
          .end_object();
    }
    if (depths)
      j.begin_object("depths")
          .value("min_m", depths->min_m)
          .value("max_m", depths->max_m)
          .value("num_filled", depths->num_filled)
          .value("max_fill_distance_m", depths->max_fill_distance_m)
          .value("num_raised_to_min_depth", depths->num_raised)
          .value("averaged", depths->averaged)
          .value("sources_kept", depths->kept)
          .value("num_dry", depths->num_dry)
          .value("courant", depths->time_steps.courant)
          .value("time_step_min_s", depths->time_steps.min_s)
          .value("time_step_median_s", depths->time_steps.median_s)
          .value("time_step_min_width_m", depths->time_steps.width_m)
          .value("time_step_min_depth_m", depths->time_steps.depth_m)
          .value("num_wet_quads", depths->time_steps.num_wet)
          .value("num_under_time_step", depths->time_steps.num_under_target)
          .end_object();
    if (zones) {
      j.begin_object("zones").value("num_polygons", zones->num_polygons);
      j.begin_array("quads_per_zone");
      for (const auto& [zone, count] : zones->counts)
        j.begin_object().value("zone", zone).value("num_quads", count).end_object();
      j.end_array().end_object();
    }
    j.begin_object("smoothing")
        .value("tiling_attempts", r.attempts)
        .array("tiling_variants", r.tiling_variants)
        .value("num_nonconvex_before", r.smooth.num_nonconvex_before)
        .value("num_untangle_sweeps", r.smooth.num_untangle_sweeps)
        .value("num_flips", r.smooth.num_flips)
        .value("num_collapses", r.smooth.num_collapses)
        .value("num_sliver_collapses", r.smooth.num_sliver_collapses)
        .value("num_corner_splits", r.smooth.num_corner_splits)
        .value("num_thin_repairs", r.smooth.num_thin_repairs)
        .end_object();
  }
  std::vector<StageTime> times = r.fields.times;
  times.insert(times.end(), more_stages.begin(), more_stages.end());
  add_stage_times(j, times);
  j.value("peak_memory_mb", process_peak_mb());  // the whole process so far
  j.end_object();
  return j.str();
}

}  // namespace isoquad
