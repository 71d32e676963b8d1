#include "app/quality_job.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "app/quality_report.h"
#include "app/summary.h"
#include "core/error.h"
#include "core/json_writer.h"
#include "core/stage_clock.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/mesh_outline.h"
#include "mesh/locate.h"

namespace isoquad {

namespace {

double triangle_signed_area(const std::vector<Point2>& p, const std::array<int, 3>& t) {
  return signed_area(p[t[0]], p[t[1]], p[t[2]]);
}

// The mesh's points into the meshing CRS; records what they were read in.
void to_meshing_crs(const QualityJobOptions& options, const ReadMesh& file,
                    const std::string& meshing_wkt, std::vector<Point2>& points,
                    QualityJobResult& r) {
  const std::string given = !options.mesh_crs.empty() ? options.mesh_crs : file.crs;
  const CrsInfo meshing = parse_crs(meshing_wkt, "the meshing CRS");
  if (given.empty()) {
    r.mesh_crs = "the meshing CRS (as the domain is projected)";
    return;
  }
  const CrsInfo from =
      parse_crs(given, options.mesh_crs.empty() ? "'" + options.mesh_path + "' (its projection)"
                                                : "--mesh-crs");
  r.mesh_crs = from.name.empty() ? given : from.name;
  const CrsTransform transform(from, meshing);
  const long failed = transform.transform(points);
  if (failed >= 0)
    throw Error(ErrorClass::crs, "crs",
                "'" + options.mesh_path + "': node " +
                    std::to_string(file_number(file.point_ids, static_cast<std::size_t>(failed))) +
                    " at " + format_point(points[failed]) + " cannot be transformed from " +
                    r.mesh_crs + " into the meshing CRS");
  r.transformed = true;
}

// The background mesh's boundary chains as closed polylines, with each vertex's arc
// length along its chain.
struct ChainLines {
  std::vector<std::vector<Point2>> lines;
  std::vector<std::vector<double>> arc;
};

ChainLines chain_lines(const BackgroundMesh& bg) {
  ChainLines c;
  for (const BoundaryChain& chain : bg.chains) {
    std::vector<Point2> line;
    std::vector<double> arc = chain.arc_length_m;
    for (int v : chain.vertices) line.push_back(bg.points[v]);
    if (!line.empty()) line.push_back(line.front());
    arc.push_back(chain.length_m);
    c.lines.push_back(std::move(line));
    c.arc.push_back(std::move(arc));
  }
  return c;
}

// Puts the mesh's boundary vertices (the ends of `edges`) that lie on the domain's
// boundary onto its chains (QuadMesh::chain and arc_m), so that the coast's departure
// from the mesh is measured as for isoquad's own meshes; counts the others and how far
// off they lie (searched up to ten times the elements' median side).
void place_on_chains(const BackgroundMesh& bg, QuadMesh& m,
                     const std::vector<std::array<int, 3>>& triangles,
                     const std::vector<std::array<int, 2>>& edges, QualityJobResult& r) {
  const int np = static_cast<int>(m.points.size());
  const std::array<double, 4> box = bounding_box(bg.points);
  r.on_boundary_tolerance_m = std::max(1e-3, 1e-7 * std::hypot(box[2] - box[0], box[3] - box[1]));
  std::vector<double> lengths;
  for (const auto& q : m.quads)
    for (int i = 0; i < 4; ++i)
      lengths.push_back(distance(m.points[q[i]], m.points[q[(i + 1) % 4]]));
  for (const auto& t : triangles)
    for (int i = 0; i < 3; ++i)
      lengths.push_back(distance(m.points[t[i]], m.points[t[(i + 1) % 3]]));
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  r.off_boundary_search_m = 10 * lengths[lengths.size() / 2];

  const ChainLines chains = chain_lines(bg);
  const PolylineIndex index(chains.lines);
  std::vector<char> boundary(np, 0);
  for (const auto& e : edges) boundary[e[0]] = boundary[e[1]] = 1;
  for (int v = 0; v < np; ++v) {
    if (!boundary[v]) continue;
    const Point2& p = m.points[v];
    PolylineIndex::Nearest n = index.nearest(p, r.on_boundary_tolerance_m);
    if (n.line >= 0) {
      const Point2 &a = chains.lines[n.line][n.segment], &b = chains.lines[n.line][n.segment + 1];
      const double length = distance(a, b);
      const double t = length > 0
                           ? std::clamp(((p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y)) /
                                            (length * length),
                                        0.0, 1.0)
                           : 0.0;
      m.chain[v] = n.line;
      m.arc_m[v] = chains.arc[n.line][n.segment] + t * length;
      ++r.num_boundary_on;
      continue;
    }
    ++r.num_boundary_off;
    n = index.nearest(p, r.off_boundary_search_m);
    if (n.line < 0)
      ++r.num_boundary_far;
    else
      r.boundary_off_max_m = std::max(r.boundary_off_max_m, n.distance);
  }
}

// Without INPUT: the domain is the mesh's outline, read in the mesh's CRS (the
// --mesh-crs or the file's own; the front end measures in it when it is projected in
// metres). Nothing of it is simplified, filled or dropped unless asked: the mesh's
// boundary vertices lie on its boundary.
FrontEndOptions outline_front_end(const QualityJobOptions& options, const ReadMesh& file,
                                  QualityJobResult& r) {
  FrontEndOptions front = options.fields.front;
  front.read = ReadParams();
  front.read.path = options.mesh_path;
  front.read.repair = options.fields.front.read.repair;
  std::vector<Point2> nodes;  // in the outline's CRS
  front.source = outline_source(file, options.mesh_path, options.mesh_crs, "--mesh-crs", &nodes);
  r.num_outline_loops = front.source->num_features;
  // Its open boundaries (a .gr3's, a MIKE mesh's codes, a .slf's .cli) stay open: -o
  // marks them so.
  for (const std::vector<int>& segment : file.open_boundaries) {
    std::vector<Point2> line;
    for (int v : segment) line.push_back(nodes[v]);
    if (line.size() >= 2) front.source_open_lines.push_back(std::move(line));
  }
  if (!front.simplify_m) front.simplify_m = 0.0;
  if (!front.min_island_area_m2) front.min_island_area_m2 = 0.0;
  if (!front.min_width_m) front.min_width_m = 0.0;
  return front;
}

// What the summary holds: the quads' figures when it has quads, their regularity when it
// has nothing else, the coast when its outline was found.
QualityParts parts_of(const QualityJobResult& r) {
  QualityParts parts;
  parts.quads = !r.quads.quads.empty();
  parts.connectivity = r.num_triangles == 0;
  parts.coast = r.coast_measured;
  return parts;
}

}  // namespace

QualityJobResult measure_mesh_file(const QualityJobOptions& options, const Progress& progress) {
  QualityJobResult r;
  progress.report("read mesh", 0.0);
  StageClock clock(r.fields.times);
  ReadMesh file = read_mesh(options.mesh_path);
  clock.lap("mesh read");
  r.format = file.format;
  r.num_skipped_elements = file.num_skipped_elements;
  std::vector<StageTime> read_times = r.fields.times;
  FieldsOptions fields = options.fields;
  const MeshDefects defects = find_mesh_defects(file);
  try {
    if (fields.front.read.path.empty() && !fields.front.source) {
      // Without INPUT, --open-groups names the groups of the measured .msh or .2dm itself.
      if (!options.fields.front.open_groups.empty()) {
        if (!options.fields.front.open_boundary_path.empty())
          throw Error(ErrorClass::usage, "options",
                      "give the open boundaries once: --open-boundary or --open-groups");
        open_boundaries_from_groups(file, options.fields.front.open_groups, options.mesh_path);
      }
      fields.front = outline_front_end(options, file, r);
      fields.front.open_groups.clear();
    }
    r.fields = build_fields(fields, progress.slice(0.05, 0.85));
  } catch (const Error& e) {
    // An outline (without INPUT) that crosses itself where elements do, or that cannot
    // be traced or is empty where elements overlap: say which.
    if (e.error_class() != ErrorClass::input || !options.fields.front.read.path.empty()) throw;
    std::string why;
    if (defects.num_degenerate > 0)
      why = std::to_string(defects.num_degenerate) +
            " element(s) without area or crossing themselves, the first " +
            defects.first_degenerate;
    else if (defects.num_duplicate_elements > 0)
      why = std::to_string(defects.num_duplicate_elements) +
            " element(s) given twice, on the same nodes, the first " + defects.first_duplicate;
    else if (defects.num_overused_sides > 0)
      why = std::to_string(defects.num_overused_sides) +
            " side(s) of three or more elements, the first between nodes " +
            std::to_string(defects.first_overused[0]) + " and " +
            std::to_string(defects.first_overused[1]) +
            ": an element given twice, or elements that overlap";
    if (why.empty()) throw;
    throw Error(e.error_class(), e.stage(), e.message() + " (the mesh has " + why + ")");
  }
  r.fields.times.insert(r.fields.times.begin(), read_times.begin(), read_times.end());
  StageClock measure_clock(r.fields.times);
  progress.report("measure", 0.85);

  for (const std::string& note : file.notes) r.warnings.push_back(note);
  for (const std::string& w : mesh_defect_warnings(defects))
    r.warnings.push_back("'" + options.mesh_path + "': " + w);
  r.point_ids = file.point_ids;
  r.quad_ids = file.quad_ids;
  r.quads.points = std::move(file.points);
  to_meshing_crs(options, file, r.fields.front.domain.crs_wkt, r.quads.points, r);
  r.quads.quads = std::move(file.quads);
  r.quads.chain.assign(r.quads.points.size(), -1);
  r.quads.arc_m.assign(r.quads.points.size(), 0.0);
  r.quads.fixed.assign(r.quads.points.size(), 0);
  QuadMesh& m = r.quads;
  std::vector<std::array<int, 3>>& triangles = file.triangles;
  const int nq = static_cast<int>(m.quads.size());

  // The mesh must lie on the domain and cover about as much: another CRS puts it
  // elsewhere, or makes it far larger or smaller (degrees read as metres).
  const TriangleLocator locator(r.fields.mesh);
  // Whether p lies in the domain, or within `share` of the size there from it (a node on
  // a coast the domain draws a little otherwise): locate() clamps a point outside to a
  // triangle, so its distance to the clamped point tells.
  auto in_domain = [&](const Point2& p, double share) {
    const Location loc = locator.locate(p);
    if (loc.triangle < 0) return false;
    if (loc.inside) return true;
    const auto& t = r.fields.mesh.triangles[loc.triangle];
    Point2 c{0, 0};
    for (int k = 0; k < 3; ++k) {
      c.x += loc.bary[k] * r.fields.mesh.points[t[k]].x;
      c.y += loc.bary[k] * r.fields.mesh.points[t[k]].y;
    }
    const double h = r.fields.size.at(r.fields.mesh, loc.triangle, loc.bary);
    return std::hypot(p.x - c.x, p.y - c.y) <= share * h;
  };
  std::size_t inside = 0;
  for (const Point2& p : m.points) inside += in_domain(p, 0.5);
  double mesh_area = 0;
  for (int q = 0; q < nq; ++q) mesh_area += std::abs(quad_area(m, q));
  for (const auto& t : triangles) mesh_area += std::abs(triangle_signed_area(m.points, t));
  const double domain_area = area(r.fields.mesh);
  if (2 * inside < m.points.size() || mesh_area < 0.1 * domain_area ||
      mesh_area > 10 * domain_area) {
    const std::array<double, 4> box = bounding_box(m.points);
    throw Error(ErrorClass::input, "quality",
                printf_string("'%s': %zu of its %zu nodes lie in the domain, and it covers %.4g "
                              "km2 where the domain covers %.4g km2 (its nodes span %s to %s in "
                              "the meshing CRS, read in %s): is the mesh in another CRS (give "
                              "it with --mesh-crs), or of another domain?",
                              options.mesh_path.c_str(), inside, m.points.size(), mesh_area / 1e6,
                              domain_area / 1e6, format_point({box[0], box[1]}).c_str(),
                              format_point({box[2], box[3]}).c_str(), r.mesh_crs.c_str()));
  }

  // Counter-clockwise elements; a file whose elements are mostly clockwise is read
  // reversed (a mesh of mixed orientation keeps it: its clockwise elements count as
  // non-convex, as they fold).
  std::size_t clockwise = 0;
  for (int q = 0; q < nq; ++q) clockwise += quad_area(m, q) < 0;
  for (const auto& t : triangles) clockwise += triangle_signed_area(m.points, t) < 0;
  if (2 * clockwise > m.quads.size() + triangles.size()) {
    r.reversed = true;
    for (auto& q : m.quads) std::reverse(q.begin(), q.end());
    for (auto& t : triangles) std::reverse(t.begin(), t.end());
  }

  r.num_triangles = triangles.size();
  r.triangle_min_angle_deg = 180, r.triangle_max_angle_deg = 0;
  std::vector<double> triangle_sizes;
  for (const auto& t : triangles) {
    const Point2 &p = m.points[t[0]], &q = m.points[t[1]], &s = m.points[t[2]];
    const Location loc = locator.locate({(p.x + q.x + s.x) / 3, (p.y + q.y + s.y) / 3});
    const double h =
        loc.triangle >= 0 ? r.fields.size.at(r.fields.mesh, loc.triangle, loc.bary) : 0.0;
    // The side of the equilateral triangle of its area, over h.
    const double side = std::sqrt(4 * std::abs(signed_area(p, q, s)) / std::sqrt(3.0));
    triangle_sizes.push_back(h > 0 ? side / h : 0.0);
    r.num_inverted_triangles += signed_area(p, q, s) <= 0;
    for (int i = 0; i < 3; ++i) {
      const Point2 &a = m.points[t[(i + 2) % 3]], &b = m.points[t[i]],
                   &c = m.points[t[(i + 1) % 3]];
      const double angle = std::atan2(std::abs(signed_area(a, b, c)) * 2,
                                      (a.x - b.x) * (c.x - b.x) + (a.y - b.y) * (c.y - b.y));
      r.triangle_min_angle_deg = std::min(r.triangle_min_angle_deg, angle * 180 / M_PI);
      r.triangle_max_angle_deg = std::max(r.triangle_max_angle_deg, angle * 180 / M_PI);
    }
  }
  // The regularity of a mesh with triangles: its interior vertices (on no side of one
  // element) whose elements' ideal angles (60 degrees a triangle's, 90 a quad's) make 360:
  // six triangles, four quads, or three triangles and two quads.
  if (!triangles.empty()) {
    std::vector<std::array<int, 2>> sides;
    std::vector<int> sixties(m.points.size(), 0);  // the ideal angles in units of 30 degrees
    auto add = [&](const int* corners, int n) {
      for (int i = 0; i < n; ++i) {
        sixties[corners[i]] += n == 3 ? 2 : 3;
        const int a = corners[i], b = corners[(i + 1) % n];
        sides.push_back({std::min(a, b), std::max(a, b)});
      }
    };
    for (const auto& t : triangles) add(t.data(), 3);
    for (const auto& q : m.quads) add(q.data(), 4);
    std::sort(sides.begin(), sides.end());
    std::vector<char> boundary(m.points.size(), 0);
    for (std::size_t i = 0; i < sides.size();) {
      std::size_t j = i;
      while (j < sides.size() && sides[j] == sides[i]) ++j;
      if (j - i == 1) boundary[sides[i][0]] = boundary[sides[i][1]] = 1;
      i = j;
    }
    std::size_t interior = 0, regular = 0;
    for (std::size_t v = 0; v < m.points.size(); ++v)
      if (sixties[v] > 0 && !boundary[v]) ++interior, regular += sixties[v] == 12;
    r.triangle_share_regular_interior = interior ? static_cast<double>(regular) / interior : 0.0;
  }
  if (!triangle_sizes.empty()) {
    std::size_t in_range = 0;
    for (double x : triangle_sizes) in_range += x >= 0.8 && x <= 1.25;
    r.triangle_share_size_08_125 = static_cast<double>(in_range) / triangle_sizes.size();
    std::nth_element(triangle_sizes.begin(), triangle_sizes.begin() + triangle_sizes.size() / 2,
                     triangle_sizes.end());
    r.triangle_size_ratio_median = triangle_sizes[triangle_sizes.size() / 2];
  }

  // The coast: along the quads' boundary edges, or with triangles along the outline of
  // every element (the quads' own boundary runs round the triangles too).
  std::vector<std::array<int, 2>> coast_edges;
  if (r.num_triangles == 0) {
    coast_edges = boundary_edges(m);
  } else {
    try {
      for (const std::vector<int>& loop :
           mesh_outline(m.points, m.quads, triangles, options.mesh_path, r.point_ids))
        for (std::size_t i = 0; i < loop.size(); ++i)
          coast_edges.push_back({loop[i], loop[(i + 1) % loop.size()]});
    } catch (const Error& e) {
      r.coast_measured = false;
      r.warnings.push_back("the coast is not measured: " + e.message());
    }
  }
  if (r.coast_measured) place_on_chains(r.fields.mesh, m, triangles, coast_edges, r);
  if (r.quads.quads.empty()) {
    r.quality.num_vertices = r.quads.points.size();  // the quads' figures stay empty
    r.warnings.push_back("'" + options.mesh_path + "' has " + std::to_string(r.num_triangles) +
                         " triangles and no quadrangle: their angles, sizes and regularity, "
                         "the coast and the D-Flow FM links are measured");
  } else {
    r.quality = measure_quality(r.quads, r.fields.mesh, r.fields.size, r.fields.cross, &r.metrics);
    if (r.fields.num_aligned_vertices > 0)
      measure_line_following(r.quads, r.fields.front.align_lines, r.quality);
    for (int q = 0; q < static_cast<int>(r.quads.quads.size()); ++q)
      r.num_quads_outside += !in_domain(quad_centroid(r.quads, q), 0.25);
  }
  if (r.num_triangles > 0 && r.coast_measured) {
    QualitySummary& q = r.quality;  // the quads' boundary's figures replaced
    q.boundary_departure_max_m = q.boundary_departure_max_h = q.boundary_departure_p95_h = 0;
    q.num_boundary_backtracks = 0;
    measure_coast(m, r.fields.mesh, r.fields.size, coast_edges, q);
  }
  // D-Flow FM's links between any two cells, with the triangles.
  if (r.num_triangles > 0) summarize_dflowfm(dflowfm_links(m, triangles), r.quality);
  r.quality.mesh_area_m2 = mesh_area;
  r.quality.domain_area_m2 = domain_area;
  if (r.num_quads_outside > 0)
    r.warnings.push_back(std::to_string(r.num_quads_outside) +
                         " quad(s) have their centroid outside the domain (by over a quarter of "
                         "the size there): their size ratio and orientation are measured "
                         "against the fields at the domain's edge (is it the same domain, with "
                         "the same --min-width and --simplify?)");
  if (r.num_boundary_off > 0)
    r.warnings.push_back(printf_string(
        "%zu of the mesh's %zu boundary vertices lie off the domain's boundary (farther than "
        "%.3g m; %s): the coast's departure is measured along the others",
        r.num_boundary_off, r.num_boundary_off + r.num_boundary_on, r.on_boundary_tolerance_m,
        r.num_boundary_far > 0
            ? printf_string("%zu farther than %.0f m", r.num_boundary_far, r.off_boundary_search_m)
                  .c_str()
            : printf_string("up to %.1f m", r.boundary_off_max_m).c_str()));
  measure_clock.lap("quality");
  progress.report("quality", 1.0);
  return r;
}

namespace {

// read_mesh's format as the summary names it: "SCHISM .gr3", "ADCIRC .14"...
std::string format_label(const std::string& format) {
  static const std::map<std::string, std::string> labels = {
      {"gr3", "SCHISM .gr3"},  {"14", "ADCIRC .14"},   {"2dm", "SMS .2dm"},
      {"msh", "Gmsh .msh"},    {"mesh", "MIKE .mesh"}, {"nc", "UGRID .nc"},
      {"slf", "TELEMAC .slf"}, {"vtu", "VTK .vtu"},    {"vtk", "VTK .vtk"},
      {"polygons", "polygons"}};
  const auto it = labels.find(format);
  return it == labels.end() ? format : it->second;
}

}  // namespace

std::string format_quality_job_summary(const QualityJobResult& r) {
  std::string out = printf_string(
      "mesh:         %s file: %zu quads, %zu triangles, %zu vertices%s%s\n",
      format_label(r.format).c_str(), r.quads.quads.size(), r.num_triangles, r.quads.points.size(),
      r.num_skipped_elements
          ? printf_string(" (%zu lines and points skipped)", r.num_skipped_elements).c_str()
          : "",
      r.reversed ? "; its elements clockwise, measured reversed" : "");
  out += "mesh CRS:     " + r.mesh_crs +
         (r.transformed ? ", transformed into the meshing CRS" : "") + "\n";
  if (r.num_outline_loops > 0)
    out += printf_string("domain from:  the mesh's outline (%zu loop(s) of boundary edges)\n",
                         r.num_outline_loops);
  const QualitySummary& q = r.quality;
  if (!r.quads.quads.empty()) {
    out += printf_string("quads:        %zu non-convex (or clockwise)%s\n", q.num_nonconvex,
                         q.num_boundary_crossings > 0 && r.num_triangles == 0
                             ? printf_string("; %zu pair(s) of boundary edges cross: the mesh "
                                             "folds over itself",
                                             q.num_boundary_crossings)
                                   .c_str()
                             : "");
    out += format_quad_shape_lines(q);
    if (r.fields.num_aligned_vertices > 0) out += format_align_line(q);
  }
  if (r.num_triangles > 0)
    out += printf_string(
        "triangles:    %zu, %zu clockwise (inverted), angles from %.1f to %.1f deg; size (the "
        "side of the equilateral triangle of its area)/h median %.3f, %.1f%% in [0.8,1.25]\n",
        r.num_triangles, r.num_inverted_triangles, r.triangle_min_angle_deg,
        r.triangle_max_angle_deg, r.triangle_size_ratio_median, 100 * r.triangle_share_size_08_125);
  if (r.num_triangles > 0 && r.quads.quads.empty())
    out += printf_string("regularity:   %.1f%% of interior vertices in six triangles\n",
                         100 * r.triangle_share_regular_interior);
  out += format_quad_connectivity_lines(q, parts_of(r));
  if (r.num_triangles > 0 && !r.quads.quads.empty())
    out += printf_string(
        "regularity:   %.1f%% of interior vertices regular (ideal angles, 60 deg a triangle's "
        "and 90 a quad's, summing to 360)\n",
        100 * r.triangle_share_regular_interior);
  return out;
}

std::string quality_job_report_json(const QualityJobResult& r, const std::string& command_line) {
  JsonWriter j;
  j.begin_object();
  add_report_header(j, command_line);
  j.begin_object("mesh")
      .value("format", r.format)
      .value("crs", r.mesh_crs)
      .value("transformed", r.transformed)
      .value("reversed", r.reversed)
      .value("num_skipped_elements", r.num_skipped_elements)
      .value("num_outline_loops", r.num_outline_loops)
      .value("num_quads_outside_domain", r.num_quads_outside);
  if (r.coast_measured)
    j.value("num_boundary_vertices_on_domain", r.num_boundary_on)
        .value("num_boundary_vertices_off_domain", r.num_boundary_off)
        .value("num_boundary_vertices_far_off_domain", r.num_boundary_far)
        .value("boundary_vertices_off_max_m", r.boundary_off_max_m);
  j.end_object();
  j.begin_object("domain");
  add_domain_summary(j, r.fields.front.summary);
  j.end_object();
  j.begin_object("sizing");
  add_sizing_report(j, r.fields);
  j.end_object();
  j.begin_object("quality")
      .value("num_quads", r.quads.quads.size())
      .value("num_vertices", r.quads.points.size())
      .value("num_triangles", r.num_triangles);
  if (r.num_triangles > 0)
    j.value("num_inverted_triangles", r.num_inverted_triangles)
        .value("triangle_min_angle_deg", r.triangle_min_angle_deg)
        .value("triangle_max_angle_deg", r.triangle_max_angle_deg)
        .value("triangle_size_ratio_median", r.triangle_size_ratio_median)
        .value("triangle_share_size_ratio_08_125", r.triangle_share_size_08_125);
  if (r.num_triangles > 0)  // by the elements' ideal angles when the mesh has quads too
    j.value(
        r.quads.quads.empty() ? "triangle_share_regular_interior" : "mixed_share_regular_interior",
        r.triangle_share_regular_interior);
  add_quality_values(j, r.quality, parts_of(r));
  if (r.fields.num_aligned_vertices > 0 && !r.quads.quads.empty()) add_align_values(j, r.quality);
  j.end_object();
  add_stage_times(j, r.fields.times);
  j.value("peak_memory_mb", process_peak_mb());
  j.end_object();
  return j.str();
}

}  // namespace isoquad
