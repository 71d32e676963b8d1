#include "app/fields_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "app/summary.h"
#include "core/error.h"
#include "core/stage_clock.h"
#include "core/text.h"
#include "fields/align_lines.h"
#include "fields/feature_size.h"
#include "fields/size_cache.h"
#include "gis/map_scale.h"
#include "gis/raster_field.h"
#include "mesh/locate.h"
#include "plot/canvas.h"

namespace isoquad {

namespace {

// The default scale of the automatic sizing (see SizingOracle): hmax gives about 2000
// quads over the domain, hmin is a tenth of it.
double default_hmin_for_area(const SizingParams& s, double area_m2) {
  if (s.hmin_m > 0) return s.hmin_m;
  if (s.constant_m) return *s.constant_m;
  const double hmax = s.hmax_m > 0 ? s.hmax_m : std::sqrt(area_m2 / 2000.0);
  return hmax / 10.0;
}

struct SingularityCounts {
  int plus = 0, minus = 0, total_quarters = 0;
};

SingularityCounts count_singularities(const std::vector<Singularity>& singularities) {
  SingularityCounts c;
  for (const Singularity& s : singularities) {
    (s.index_quarters > 0 ? c.plus : c.minus) += 1;
    c.total_quarters += s.index_quarters;
  }
  return c;
}

// Error(usage) when `quads` is over options.max_quads (`how`: how they were counted;
// `smallest`: the smallest size counted).
void check_quad_budget(double quads, const char* how, double smallest, const Domain& domain,
                       const FieldsOptions& options) {
  if (!(options.max_quads > 0) || !(quads > options.max_quads)) return;
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "the sizes ask for about %.3g quads (%s; %.6g km2, sizes from %.6g m), over the "
      "limit of %.0f (--max-quads; 0: none). A quad takes about 2 to 5 KB of memory at the "
      "peak: check the sizes' units (metres), or raise --max-quads",
      quads, how, area(domain) / 1e6, smallest, options.max_quads);
  throw Error(ErrorClass::usage, "sizing", buf);
}

// Background vertices a quad, at least, at the default --background-factor (0.25):
// Corsica automatic has 10.2, France automatic 10.4, two squares in a water domain 9.
constexpr double kBackgroundVerticesPerQuad = 4.0;

// Quads of size h cover about h^2 each (France at a uniform 11 km: 0.95 of its area over
// h^2): no mesh with every size at most hmax comes under half its area over hmax^2.
constexpr double kQuadsPerAreaOverHmax2 = 0.5;

// Error(usage) as soon as the domain is projected when --hmax alone asks for more quads
// than options.max_quads: a size meant in km (--hmax 8 over Brittany's water) would
// otherwise first sample the boundary at hmin (tens of seconds and gigabytes) before the
// estimate on the sizes stops it. Only --time-step raises sizes over hmax. `scale`: the
// meshing CRS's where the sizes are the ground's (hmax then holds on the ground).
void check_hmax_budget(const Domain& domain, const MapScale* scale, const FieldsOptions& options) {
  const SizingParams& sizing = options.sizing;
  if (!(sizing.hmax_m > 0) || sizing.time_step_s > 0) return;
  const double ground = scale ? ground_area(domain, *scale) : area(domain);
  check_quad_budget(kQuadsPerAreaOverHmax2 * ground / (sizing.hmax_m * sizing.hmax_m),
                    "at least that: every size is at most --hmax", sizing.hmax_m, domain, options);
}

// Edges of the coarse mesh the cross field is solved on, for large background meshes
// (FieldsOptions::coarse_cross_above), in sizes h (the background mesh's are 0.5 by
// default). Against the field solved on the background mesh, Corsica automatic at hmax 8
// km: 1.6 degrees on average (0.75: the same; 2: 4.6).
constexpr double kCoarseEdge = 1.0;
// Away from the boundary the field turns over distances like the distance d to it: the
// coarse mesh's edges grow to kCoarseGrowth d there, where that is longer than the sizes.
constexpr double kCoarseGrowth = 0.25;

// The sizing sources, the background mesh and the sizes at its vertices (stages
// "sizing sources", "background mesh" and "sizing field"). The sources and the size
// cache are this function's own: they are gone before the cross field's solve, the
// largest allocation of a large domain.
void build_mesh_and_sizes(const Domain& domain, const FieldsOptions& options, FieldsResult& r,
                          std::optional<BackgroundMesh>& coarse, StageClock& timer,
                          const Progress& progress) {
  progress.report("sizing", 0.0);
  SizingParams sizing = options.sizing;
  sizing.open_parts = r.front.open_boundary_parts;  // for --size-expr's c
  if (!r.front.open_boundary_lines.empty()) sizing.open_tolerance_m = open_line_tolerance(r.front);
  sizing.share_depths = r.depths;
  SizingOracle oracle(domain, sizing);
  r.sizing = oracle.summary();
  r.depths = oracle.depths() && oracle.depths()->has_shareable() ? oracle.depths() : nullptr;
  r.scale = oracle.scale();
  double smallest = std::numeric_limits<double>::infinity();
  const double estimate = estimate_num_quads(domain, [&oracle, &smallest](const Point2& p) {
    const double h = oracle(p);
    smallest = std::min(smallest, h);
    return h;
  });
  check_quad_budget(estimate, "estimated on a grid", smallest, domain, options);
  // The grid misses a band of small sizes along the boundary (--size-expr "max(c, 1)",
  // sizes from the distance to the coast): there every boundary edge of the mesh is a
  // quad's side, about h long, so its quads are at least half the boundary's length over
  // its sizes, sampled at its vertices and edges' midpoints. A size of 0 there (c alone)
  // is refused by the oracle itself.
  double boundary_quads = 0.0;
  auto add_ring = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2& a = ring[i];
      const Point2& b = ring[(i + 1) % ring.size()];
      const double h = std::min(oracle(a), oracle({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}));
      smallest = std::min(smallest, h);
      boundary_quads += std::hypot(b.x - a.x, b.y - a.y) / h;
    }
  };
  for (const Polygon& poly : domain.polygons) {
    add_ring(poly.outer);
    for (const Ring& hole : poly.holes) add_ring(hole);
  }
  check_quad_budget(0.5 * boundary_quads, "at least that along the boundary", smallest, domain,
                    options);
  // The background mesh has about 9 to 10 vertices a quad at the default factor (0.25),
  // and 1 / factor^2 as many at others: a tiny --background-factor (its least, 0.001,
  // asks for 62,500 times as many) is refused here, not after the background mesh has
  // filled the memory up to its limit.
  const double background_vertices = kBackgroundVerticesPerQuad *
                                     std::max(estimate, 0.5 * boundary_quads) *
                                     std::pow(0.25 / options.background_factor, 2);
  const std::size_t vertex_limit = BackgroundMeshParams{}.max_num_vertices;
  if (background_vertices > static_cast<double>(vertex_limit))
    throw Error(ErrorClass::usage, "background",
                printf_string("--background-factor %g asks for about %.3g background vertices "
                              "(at least %g a quad at 0.25, times (0.25 / %g)^2), over the "
                              "background mesh's limit of %zu: give a larger factor, or "
                              "larger sizes",
                              options.background_factor, background_vertices,
                              kBackgroundVerticesPerQuad, options.background_factor, vertex_limit));
  timer.lap("sizing sources");

  progress.report("background", 0.2);  // to 0.6 as the background mesh is built
  BackgroundMeshParams bp;
  const double factor = 2.0 * options.background_factor;  // tiles are 2h wide
  // Refinement evaluates the size many times, at scattered points: it reads a quadtree
  // cache (cells at most half the local size; bilinear values there are close to the
  // graded field, which changes by at most K times the cell side) instead of the sources.
  // A uniform size has nothing to cache (France at 1.5 km: 4 million cells, 150 MB).
  std::optional<SizeCache> cache;
  if (!oracle.is_uniform()) {
    std::vector<std::array<double, 4>> components;
    for (const Polygon& poly : domain.polygons) {
      std::array<double, 4> b{poly.outer[0].x, poly.outer[0].y, poly.outer[0].x, poly.outer[0].y};
      for (const Point2& p : poly.outer)
        b = {std::min(b[0], p.x), std::min(b[1], p.y), std::max(b[2], p.x), std::max(b[3], p.y)};
      components.push_back(b);
    }
    cache.emplace(
        bounding_box(domain), [&oracle](const Point2& p) { return oracle(p); }, 0.5, 18,
        std::move(components));
  }
  const auto size_at = [&cache, &oracle](const Point2& p) {
    return cache ? (*cache)(p) : oracle(p);
  };
  bp.max_edge_m = [&size_at, factor](const Point2& p) { return factor * size_at(p); };
  const Progress background = progress.slice(0.2, 0.6);
  bp.progress = [&background](double done) { background.report("background", done); };
  r.mesh = build_background_mesh(domain, bp);
  // The triangulation's many small blocks, freed, would otherwise stay resident beside
  // the cross field's large ones.
  release_free_memory();
  timer.lap("background mesh");

  progress.report("sizing", 0.6);
  r.size = sample_sizing_field(r.mesh, oracle, options.sizing.gradation);
  if (!r.size.size_m.empty())
    check_quad_budget(
        predicted_num_quads(r.mesh, r.size), "the graded sizes on the background mesh",
        *std::min_element(r.size.size_m.begin(), r.size.size_m.end()), domain, options);
  timer.lap("sizing field");
  // A large background mesh, within the budget: a coarse one too, with edges up to
  // kCoarseEdge times the sizes, for the cross field's solve (boundary_field).
  if (options.coarse_cross_above > 0 && r.mesh.points.size() > options.coarse_cross_above &&
      options.cross.source != CrossSource::constant) {
    BackgroundMeshParams coarse_params;
    // Sampled every hmin (at most 400,000 samples): d need not be closer than the sizes.
    const CoastDistance boundary_distance(domain, PolylineIndex(), 0.0,
                                          std::max(smallest, perimeter(domain) / 400000.0));
    coarse_params.max_edge_m = [&size_at, &boundary_distance](const Point2& p) {
      return kCoarseEdge * std::max(size_at(p), kCoarseGrowth * boundary_distance(p));
    };
    coarse = build_background_mesh(domain, coarse_params);
    timer.lap("coarse mesh");
  }
}

// The boundary-aligned field, and the lines' crosses (`lines`, on `mesh`: --align) fixed
// as the boundary's. With a coarse mesh of the domain, solved there (with the lines'
// crosses on it) and interpolated (in 4 theta), the boundary vertices and those the
// lines fix keeping their own crosses.
CrossField boundary_field(const BackgroundMesh& mesh, const SizingField& size, double conformal,
                          const BackgroundMesh* coarse, const LineCrosses* lines,
                          const std::vector<std::vector<Point2>>& align_lines) {
  if (!coarse)
    return boundary_aligned_cross_field(mesh, size.size_m, conformal,
                                        lines ? &lines->crosses : nullptr);
  // Each locator lives only while used: the solve between them is the stage's peak.
  std::vector<double> coarse_size(coarse->points.size());
  {
    const TriangleLocator fine(mesh);
    for (std::size_t v = 0; v < coarse->points.size(); ++v) {
      const Location l = fine.locate(coarse->points[v]);
      coarse_size[v] = size.at(mesh, l.triangle, l.bary);
    }
  }
  std::optional<LineCrosses> coarse_lines;
  if (lines) coarse_lines = line_crosses(*coarse, align_lines);
  const CrossField solved = boundary_aligned_cross_field(
      *coarse, coarse_size, conformal, coarse_lines ? &coarse_lines->crosses : nullptr);
  const TriangleLocator locator(*coarse);
  FixedCrosses fixed = boundary_crosses(mesh);
  if (lines)
    for (std::size_t v = 0; v < mesh.points.size(); ++v)
      if (lines->crosses.is_fixed[v] && !fixed.is_fixed[v]) {
        fixed.is_fixed[v] = 1;
        fixed.uc[v] = lines->crosses.uc[v];
        fixed.us[v] = lines->crosses.us[v];
      }
  CrossField field;
  field.angle_rad.resize(mesh.points.size());
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (fixed.is_fixed[v]) {
      field.angle_rad[v] = cross_angle_of(fixed.uc[v], fixed.us[v]);
      continue;
    }
    const Location l = locator.locate(mesh.points[v]);
    field.angle_rad[v] = cross_angle_at(*coarse, solved, l.triangle, l.bary);
  }
  return field;
}

}  // namespace

void build_fields_on_domain(const Domain& domain, const FieldsOptions& options, FieldsResult& r,
                            const Progress& progress) {
  if (!(options.background_factor > 0 && options.background_factor <= 1))
    throw Error(ErrorClass::usage, "background", "--background-factor must be in (0, 1]");
  StageClock timer(r.times);
  std::optional<BackgroundMesh> coarse;
  build_mesh_and_sizes(domain, options, r, coarse, timer, progress);
  release_free_memory();  // the sources' and the cache's blocks too

  progress.report("cross", 0.8);
  // --align: the lines' crosses, and the lines that lie nowhere in the domain.
  const std::vector<std::vector<Point2>>& align_lines = r.front.align_lines;
  std::optional<LineCrosses> lines;
  if (!r.front.summary.align_path.empty()) {
    const std::string& path = r.front.summary.align_path;
    const std::size_t num_lines = r.front.summary.align_num_lines;
    if (options.cross.source == CrossSource::constant)
      throw Error(ErrorClass::usage, "options",
                  "--align shapes the boundary-aligned cross field: not with --cross-angle");
    lines = line_crosses(r.mesh, align_lines);
    // The file's lines of which some piece lies inside.
    std::vector<char> reached(num_lines, 0);
    for (std::size_t k = 0; k < align_lines.size(); ++k)
      if (lines->line_inside[k]) reached[r.front.align_line_of[k]] = 1;
    const auto outside = static_cast<std::size_t>(std::count(reached.begin(), reached.end(), 0));
    const bool none = outside == num_lines || lines->num_fixed == 0;
    const std::string none_inside = "'" + path + "': none of its " + std::to_string(num_lines) +
                                    " line(s) lies inside the domain, away from its boundary";
    if (none && !options.front.align_optional) throw Error(ErrorClass::input, "align", none_inside);
    // Once, though a retried tiling builds the fields again.
    const std::string warning = none ? none_inside + ": the field follows the boundary alone"
                                     : std::to_string(outside) + " of the " +
                                           std::to_string(num_lines) + " lines of '" + path +
                                           "' lie wholly outside the domain";
    std::vector<std::string>& warnings = r.front.summary.warnings;
    if ((none || outside > 0) &&
        std::find(warnings.begin(), warnings.end(), warning) == warnings.end())
      warnings.push_back(warning);
    r.num_aligned_vertices = lines->num_fixed;
    if (none) lines.reset();
  }
  const LineCrosses* fixed_lines = lines ? &*lines : nullptr;
  if (options.cross.source != CrossSource::constant)
    r.num_cross_solve_vertices = coarse ? coarse->points.size() : r.mesh.points.size();
  switch (options.cross.source) {
    case CrossSource::boundary:
      r.cross = boundary_field(r.mesh, r.size, options.cross.conformal, coarse ? &*coarse : nullptr,
                               fixed_lines, align_lines);
      break;
    case CrossSource::constant: r.cross = constant_cross_field(r.mesh, options.cross.angle_deg); break;
    case CrossSource::raster: {
      const CrsInfo crs{domain.crs_wkt, domain.crs_name, false, true, 1.0};
      RasterField raster(options.cross.raster_path, "--cross-raster", crs, bounding_box(domain));
      // Where the raster has no data, the boundary-aligned field fills in.
      r.cross = boundary_field(r.mesh, r.size, options.cross.conformal, coarse ? &*coarse : nullptr,
                               fixed_lines, align_lines);
      std::size_t num_taken = 0;
      for (std::size_t v = 0; v < r.mesh.points.size(); ++v) {
        const double deg = raster.sample(r.mesh.points[v]);
        if (std::isnan(deg)) continue;
        // Degrees counter-clockwise from the meshing CRS's x axis, modulo 90.
        r.cross.angle_rad[v] = std::fmod(std::fmod(deg, 90.0) + 90.0, 90.0) * M_PI / 180.0;
        ++num_taken;
      }
      if (num_taken == 0)
        throw Error(ErrorClass::input, "cross field",
                    "--cross-raster '" + options.cross.raster_path +
                        "' has no angle anywhere over the domain (check its extent, its CRS "
                        "and its nodata value)");
      break;
    }
  }
  r.singularities = cross_field_singularities(r.mesh, r.cross);
  timer.lap("cross field");
  progress.report("fields", 1.0);
}

void clean_at_sizes(FrontEndOptions& front, const SizingParams& sizing) {
  front.warn_distortion = !sizing.ground_sizes;
  front.map_scale_for_domain = [sizing](const Domain& domain) {
    std::shared_ptr<const MapScale> scale =
        sizing.ground_sizes ? domain_map_scale(domain) : nullptr;
    return scale && scale->max_error() > kGroundScaleTolerance ? scale : nullptr;
  };
  front.target_size_for_domain = [sizing, given = front.target_size_m](const Domain& domain,
                                                                       const MapScale* scale) {
    auto size = [&](double area_m2) {
      return given > 0 ? given : default_hmin_for_area(sizing, area_m2);
    };
    if (scale) return scale->min() * size(ground_area(domain, *scale));
    return size(area(domain));
  };
}

FieldsResult build_fields(const FieldsOptions& options, const Progress& progress) {
  FieldsResult r;
  FrontEndOptions front = options.front;
  clean_at_sizes(front, options.sizing);
  front.target_size_for_domain = [target = front.target_size_for_domain, &options](
                                     const Domain& domain, const MapScale* scale) {
    check_hmax_budget(domain, scale, options);
    return target(domain, scale);
  };
  StageClock clock(r.times);
  r.front = build_planar_domain(front, progress.slice(0.0, 0.2));
  clock.lap("front end");
  build_fields_on_domain(r.front.domain, options, r, progress.slice(0.2, 1.0));
  return r;
}

SizingField ground_size_field(const FieldsResult& r) {
  SizingField ground = r.size;
  if (r.scale)
    for (std::size_t v = 0; v < ground.size_m.size(); ++v)
      ground.size_m[v] /= r.scale->at(r.mesh.points[v]);
  return ground;
}

double predicted_quads(const FieldsResult& r) {
  return std::max(predicted_num_quads(r.mesh, r.size),
                  3.0 * static_cast<double>(r.front.domain.polygons.size()));
}

std::string format_fields_summary(const FieldsResult& r) {
  std::ostringstream os;
  char buf[256];
  os << "sizing:       ";
  for (std::size_t i = 0; i < r.sizing.sources.size(); ++i) os << (i ? " + " : "") << r.sizing.sources[i];
  // A constant size alone has no bounds: "none" rather than 0 and inf.
  const std::string hmin = r.sizing.hmin_m > 0 ? printf_string("%.6g m", r.sizing.hmin_m) : "none";
  const std::string hmax =
      std::isfinite(r.sizing.hmax_m) ? printf_string("%.6g m", r.sizing.hmax_m) : "none";
  os << "; hmin " << hmin << ", hmax " << hmax
     << printf_string(", gradation %.3g\n", r.sizing.gradation);
  if (r.sizing.scale_applied)
    os << printf_string(
        "map scale:    the meshing CRS's scale is %.4g .. %.4g over the domain: the sizes in "
        "metres are the ground's, multiplied by it in the CRS (--size-scale crs: sizes in "
        "its metres)\n",
        r.sizing.scale_min, r.sizing.scale_max);
  if (r.sizing.num_narrow_sites > 0) {
    std::snprintf(buf, sizeof buf,
                  "narrow sizes: one element across the channels, inlets and spits %.6g to %.6g m "
                  "wide (hmin/2 to --cells-across x hmin), down to %.6g m (%zu medial points)\n",
                  r.sizing.narrow_min_width_m, r.sizing.narrow_max_width_m,
                  r.sizing.narrow_floor_m, r.sizing.num_narrow_sites);
    os << buf;
  }
  if (!r.size.size_m.empty()) {
    const std::vector<double> ground = ground_size_field(r).size_m;
    const auto [lo, hi] = std::minmax_element(ground.begin(), ground.end());
    std::snprintf(buf, sizeof buf,
                  "size field:   %.6g .. %.6g m%s on %zu background vertices; about %.0f quads\n",
                  *lo, *hi, r.scale ? " on the ground" : "", ground.size(), predicted_quads(r));
    os << buf;
  }
  if (r.sizing.time_step_s > 0) {
    std::snprintf(buf, sizeof buf,
                  "dt floor:     sizes for %.6g s at a Courant number of %.3g set at %zu "
                  "background vertices",
                  r.sizing.time_step_s, r.sizing.courant, r.size.num_set_by_time_step);
    os << buf;
    if (r.size.num_set_by_time_step > 0) {
      std::snprintf(buf, sizeof buf, " (up to %.6g m%s)", r.size.max_time_step_size_m,
                    r.size.max_time_step_size_m > r.sizing.hmax_m ? ", above hmax" : "");
      os << buf;
    } else {
      os << " (the other sources' sizes are larger everywhere)";
    }
    os << "\n";
  }
  std::snprintf(buf, sizeof buf, "background:   %zu vertices, %zu triangles, %zu boundary chains\n",
                r.mesh.points.size(), r.mesh.triangles.size(), r.mesh.chains.size());
  os << buf;
  const SingularityCounts c = count_singularities(r.singularities);
  std::snprintf(buf, sizeof buf,
                "cross field:  %zu singularities (%d of index +1/4, %d of index -1/4 or less; "
                "total index %d/4)",
                r.singularities.size(), c.plus, c.minus, c.total_quarters);
  os << buf;
  if (r.num_cross_solve_vertices > 0 && r.num_cross_solve_vertices != r.mesh.points.size())
    os << "; solved on a coarser mesh of " << r.num_cross_solve_vertices
       << " vertices and interpolated";
  os << "\n";
  if (r.num_aligned_vertices > 0)
    os << "aligned:      " << r.num_aligned_vertices << " background vertices along the "
       << r.front.summary.align_num_lines << " line(s) of " << r.front.summary.align_path << "\n";
  os << "times:       ";
  for (const StageTime& t : r.times) {
    std::snprintf(buf, sizeof buf, " %s %.3f s %.0f MB;", t.stage.c_str(), t.seconds, t.peak_mb);
    os << buf;
  }
  os << "\n";
  return os.str();
}

void add_sizing_report(JsonWriter& j, const FieldsResult& r) {
  j.value("hmin_m", r.sizing.hmin_m)
      .value("hmax_m", r.sizing.hmax_m)
      .value("gradation", r.sizing.gradation)
      .array("sources", r.sizing.sources)
      .value("narrow_medial_points", r.sizing.num_narrow_sites)
      .value("predicted_quads", predicted_quads(r))
      .value("map_scale_min", r.sizing.scale_min)
      .value("map_scale_max", r.sizing.scale_max)
      .value("map_scale_applied", r.sizing.scale_applied);
  if (r.sizing.time_step_s > 0)
    j.value("time_step_s", r.sizing.time_step_s)
        .value("courant", r.sizing.courant)
        .value("num_set_by_time_step", r.size.num_set_by_time_step)
        .value("max_time_step_size_m", r.size.max_time_step_size_m);
  if (!r.size.size_m.empty()) {
    const std::vector<double> ground = ground_size_field(r).size_m;
    const auto [lo, hi] = std::minmax_element(ground.begin(), ground.end());
    j.value("size_min_m", *lo).value("size_max_m", *hi);
  }
}

void add_background_report(JsonWriter& j, const FieldsResult& r) {
  const SingularityCounts c = count_singularities(r.singularities);
  j.begin_object("background")
      .value("num_vertices", r.mesh.points.size())
      .value("num_triangles", r.mesh.triangles.size())
      .value("num_boundary_chains", r.mesh.chains.size())
      .value("num_singularities", r.singularities.size())
      .end_object();
  j.begin_object("cross_field")
      .value("num_singularities", r.singularities.size())
      .value("num_index_plus_quarter", c.plus)
      .value("num_index_minus_quarter_or_less", c.minus)
      .value("total_index_quarters", c.total_quarters);
  if (r.num_cross_solve_vertices > 0) j.value("num_solve_vertices", r.num_cross_solve_vertices);
  if (r.num_aligned_vertices > 0)
    j.value("align_path", r.front.summary.align_path)
        .value("align_num_lines", r.front.summary.align_num_lines)
        .value("num_aligned_vertices", r.num_aligned_vertices);
  j.end_object();
}

void add_stage_times(JsonWriter& j, const std::vector<StageTime>& times) {
  j.begin_array("stages");
  for (const StageTime& t : times)
    j.begin_object()
        .value("stage", t.stage)
        .value("seconds", t.seconds)
        .value("peak_mb", t.peak_mb)
        .end_object();
  j.end_array();
}

std::string fields_report_json(const FieldsResult& r, const std::string& command_line) {
  JsonWriter j;
  j.begin_object();
  add_report_header(j, command_line);
  j.begin_object("domain");
  add_domain_summary(j, r.front.summary);
  j.end_object();
  j.begin_object("sizing");
  add_sizing_report(j, r);
  j.end_object();
  add_background_report(j, r);
  add_stage_times(j, r.times);
  j.value("peak_memory_mb", process_peak_mb());  // the whole process so far
  j.end_object();
  return j.str();
}

}  // namespace isoquad
