#include "app/front_end.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "core/error.h"
#include "core/text.h"
#include "domain/exclude_areas.h"
#include "domain/separate_rings.h"
#include "gis/crs.h"
#include "gis/mesh_outline.h"
#include "gis/raster_domain.h"
#include "gis/read_lines.h"
#include "gis/read_mesh.h"
#include "gis/read_points.h"

namespace isoquad {

namespace {

// The default --hairline, a share of --min-width.
constexpr double kHairlineShare = 0.02;

struct ProjectedLines {
  std::vector<std::vector<Point2>> lines;
  std::vector<double> sag_m;  // by line: the largest gap between a projected segment and its chord
  std::vector<int> line_of;   // by line: the input line it comes from
  long failed_line = -1;      // the first line with a point that cannot be transformed
  std::size_t num_source_lines = 0;  // the lines read (read_projected_lines)
};

// Each segment cut into 16, so that the lines follow the segments' curved images, then
// transformed. With `by_segment`, each segment of the input becomes two lines of its
// own, its curved image and the chord between its ends, both with its sag.
ProjectedLines project_lines(const std::vector<std::vector<Point2>>& lines, const CrsInfo& from,
                             const CrsInfo& to, bool by_segment) {
  constexpr int kPieces = 16;
  ProjectedLines out;
  CrsTransform t(from, to);
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const auto& line = lines[l];
    std::vector<Point2> dense;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Point2 &a = line[i], &b = line[i + 1];
      for (int k = 0; k < kPieces; ++k)
        dense.push_back({a.x + (b.x - a.x) * k / kPieces, a.y + (b.y - a.y) * k / kPieces});
    }
    dense.push_back(line.back());
    if (t.transform(dense) >= 0) {
      out.failed_line = static_cast<long>(l);
      return out;
    }
    std::vector<double> sags;
    for (std::size_t i = 0; i + kPieces < dense.size(); i += kPieces) {
      const Point2 &a = dense[i], &b = dense[i + kPieces];
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      double sag = 0.0;
      for (int k = 1; k < kPieces && len > 0; ++k) {
        const Point2& p = dense[i + k];
        sag = std::max(sag, std::abs((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / len);
      }
      sags.push_back(sag);
    }
    if (by_segment) {
      for (std::size_t i = 0; i < sags.size(); ++i) {
        out.lines.emplace_back(dense.begin() + i * kPieces, dense.begin() + (i + 1) * kPieces + 1);
        out.lines.push_back({dense[i * kPieces], dense[(i + 1) * kPieces]});
        out.sag_m.insert(out.sag_m.end(), 2, sags[i]);
        out.line_of.insert(out.line_of.end(), 2, static_cast<int>(l));
      }
    } else {
      out.lines.push_back(std::move(dense));
      out.sag_m.push_back(*std::max_element(sags.begin(), sags.end()));
      out.line_of.push_back(static_cast<int>(l));
    }
  }
  return out;
}

// The runs of consecutive segments of `lines` whose boxes come within `margin` of `box`
// (xmin, ymin, xmax, ymax), as lines of their own, with the index of the line each
// comes from: a file of lines over a continent walked only where the domain is.
void keep_near_box(const std::vector<std::vector<Point2>>& lines, const std::array<double, 4>& box,
                   double margin, std::vector<std::vector<Point2>>& pieces,
                   std::vector<int>& line_of_piece) {
  for (std::size_t l = 0; l < lines.size(); ++l) {
    const auto& line = lines[l];
    bool open = false;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const Point2 &a = line[i], &b = line[i + 1];
      const bool near =
          std::max(a.x, b.x) >= box[0] - margin && std::min(a.x, b.x) <= box[2] + margin &&
          std::max(a.y, b.y) >= box[1] - margin && std::min(a.y, b.y) <= box[3] + margin;
      if (!near) {
        open = false;
        continue;
      }
      if (!open) {
        pieces.push_back({a});
        line_of_piece.push_back(static_cast<int>(l));
        open = true;
      }
      pieces.back().push_back(b);
    }
  }
}

// The lines of `path` (read_lines; a modelling package's line file in the input's CRS)
// projected to the meshing CRS. Throws Error(crs) for a point that cannot be.
ProjectedLines read_projected_lines(const std::string& path, const std::string& layer,
                                    const std::string& what, const CrsInfo& source_crs,
                                    const CrsInfo& meshing_crs, bool by_segment) {
  const SourceLines lines = read_lines(path, layer, what, &source_crs);
  ProjectedLines p = project_lines(lines.lines, lines.crs, meshing_crs, by_segment);
  if (p.failed_line >= 0)
    throw Error(ErrorClass::crs, what,
                "'" + path + "': a point of line " + std::to_string(p.failed_line + 1) +
                    " cannot be transformed from " + lines.crs.name + " to the meshing CRS");
  p.num_source_lines = lines.lines.size();
  return p;
}

// The domain's edges are projected as chords between their ends; lines with more
// vertices than such an edge run along its curved image (500 m off the chord of a
// 150 km edge in lon/lat). A domain edge whose ends lie on the lines and the image of
// whose middle (in the source CRS) does too is added to them as it is, a chord.
void add_domain_chords(FrontEndResult& result, const CrsInfo& source_crs,
                       const CrsInfo& meshing_crs) {
  const double tolerance = open_line_tolerance(result);
  const PolylineIndex index(result.open_boundary_lines, result.open_boundary_slack_m);
  const CrsTransform to_source(meshing_crs, source_crs), from_source(source_crs, meshing_crs);
  std::vector<std::vector<Point2>> chords;
  std::vector<int> groups;  // each chord's line's group
  auto visit = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 &a = ring[i], &b = ring[(i + 1) % ring.size()];
      if (!index.near(a, tolerance) || !index.near(b, tolerance) ||
          index.near({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}, tolerance))
        continue;
      Point2 sa = a, sb = b;
      if (!to_source.transform(sa) || !to_source.transform(sb)) continue;
      if (source_crs.geographic) sb.x += 360.0 * std::round((sa.x - sb.x) / 360.0);
      Point2 middle{0.5 * (sa.x + sb.x), 0.5 * (sa.y + sb.y)};
      if (!from_source.transform(middle)) continue;
      const PolylineIndex::Nearest nearest = index.nearest(middle, tolerance);
      if (nearest.line < 0) continue;
      chords.push_back({a, b});
      groups.push_back(result.open_boundary_line_group[nearest.line]);
    }
  };
  for (const Polygon& polygon : result.domain.polygons) {
    visit(polygon.outer);
    for (const Ring& hole : polygon.holes) visit(hole);
  }
  for (std::size_t k = 0; k < chords.size(); ++k) {
    result.open_boundary_lines.push_back(std::move(chords[k]));
    result.open_boundary_slack_m.push_back(0.0);
    result.open_boundary_line_group.push_back(groups[k]);
  }
}

// The runs of the domain's rings along the open lines (FrontEndResult::open_boundary_parts),
// as the summary measures their length: each edge cut into pieces of about the tolerance
// (at most 256), a piece open when both its ends lie within the tolerance of the lines; a
// run may so start or end within an edge (where the simplification joined a vertex on
// the lines to one off them).
std::vector<std::vector<Point2>> open_parts(const FrontEndResult& result) {
  const double tolerance = open_line_tolerance(result);
  const PolylineIndex index(result.open_boundary_lines, result.open_boundary_slack_m);
  std::vector<std::vector<Point2>> parts;
  auto visit = [&](const Ring& ring) {
    const std::size_t n = ring.size();
    // The pieces in order round the ring: their edge, their number there and its count.
    struct Piece {
      std::size_t edge;
      int k, pieces;
    };
    std::vector<Piece> pieces;
    std::vector<char> near_end;  // whether each piece's end lies on the lines
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 &a = ring[i], &b = ring[(i + 1) % n];
      const int count = static_cast<int>(
          std::clamp(std::ceil(distance(a, b) / std::max(tolerance, 1e-9)), 1.0, 256.0));
      for (int k = 1; k <= count; ++k) {
        const double t = static_cast<double>(k) / count;
        pieces.push_back({i, k, count});
        near_end.push_back(index.near({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}, tolerance));
      }
    }
    const std::size_t m = pieces.size();
    auto point = [&](std::size_t p, int k) {  // the point at k of piece p's edge
      const Point2 &a = ring[pieces[p].edge], &b = ring[(pieces[p].edge + 1) % n];
      const double t = static_cast<double>(k) / pieces[p].pieces;
      return Point2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    };
    // Each piece's group: -1 when not open, else that of the line nearest its middle
    // (open_boundary_line_group), so that a run ends where two lines meet.
    std::vector<int> group(m, -1);
    for (std::size_t p = 0; p < m; ++p) {
      if (!near_end[p] || !near_end[(p + m - 1) % m]) continue;
      const Point2 a = point(p, pieces[p].k - 1), b = point(p, pieces[p].k);
      const int line = index.nearest({0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}, tolerance).line;
      const auto& groups = result.open_boundary_line_group;
      group[p] = line >= 0 && static_cast<std::size_t>(line) < groups.size() ? groups[line] : 0;
    }
    std::size_t start = 0;  // a piece where the group changes: no run wraps round it
    while (start < m && group[start] == group[(start + m - 1) % m]) ++start;
    if (start == m) {  // one group all round
      if (group[0] < 0) return;
      std::vector<Point2> whole(ring.begin(), ring.end());
      whole.push_back(ring.front());
      parts.push_back(std::move(whole));
      return;
    }
    std::vector<Point2> run;
    for (std::size_t j = 0; j < m; ++j) {
      const std::size_t p = (start + j) % m;
      if (group[p] < 0) continue;
      if (run.empty()) run.push_back(point(p, pieces[p].k - 1));
      const bool last = group[(p + 1) % m] != group[p];
      if (pieces[p].k == pieces[p].pieces || last) run.push_back(point(p, pieces[p].k));
      if (last) parts.push_back(std::move(run)), run.clear();
    }
  };
  for (const Polygon& polygon : result.domain.polygons) {
    visit(polygon.outer);
    for (const Ring& hole : polygon.holes) visit(hole);
  }
  return parts;
}

// A mesh file given as INPUT (hgrid.gr3, a .2dm...): its outline as the polygons, and a
// .gr3's open boundaries as lines in its CRS (`open_lines`).
SourceData read_mesh_source(const FrontEndOptions& options,
                            std::vector<std::vector<Point2>>& open_lines) {
  const ReadParams& read = options.read;
  const std::string kind = std::string("--domain ") + domain_kind_name(options.kind);
  const std::pair<bool, std::string> selections[] = {{!read.layer.empty(), "--layer"},
                                                     {!read.where.empty(), "--where"},
                                                     {read.bbox.has_value(), "--bbox"},
                                                     {!options.clip_path.empty(), "--clip"},
                                                     {options.kind != DomainKind::land, kind}};
  for (const auto& [given, option] : selections)
    if (given)
      throw Error(ErrorClass::usage, "read",
                  "'" + read.path + "' is a mesh, whose outline is the domain: " + option +
                      " selects from a vector file's polygons");
  ReadMesh mesh = read_mesh(read.path);
  if (!options.open_groups.empty()) {
    if (!options.open_boundary_path.empty())
      throw Error(ErrorClass::usage, "options",
                  "give the open boundaries once: --open-boundary or --open-groups");
    open_boundaries_from_groups(mesh, options.open_groups, read.path);
  }
  std::vector<Point2> nodes;  // in the outline's CRS
  SourceData source = outline_source(mesh, read.path, read.src_crs, "--src-crs", &nodes);
  for (const std::vector<int>& segment : mesh.open_boundaries) {
    std::vector<Point2> line;
    for (int v : segment) line.push_back(nodes[v]);
    if (line.size() >= 2) open_lines.push_back(std::move(line));
  }
  for (const std::string& note : mesh.notes) source.warnings.push_back(note);
  if (mesh.num_flux_boundaries > 0 && options.open_boundary_path.empty())
    source.warnings.push_back(std::to_string(mesh.num_flux_boundaries) +
                              " flux boundary(ies) of '" + read.path +
                              "' (a river's inflow, among its land boundaries) are open "
                              "boundaries of the new mesh");
  if (mesh.open_boundaries.empty() && !mesh.curve_groups.empty() &&
      options.open_boundary_path.empty()) {
    source.warnings.push_back(curve_groups_kind(mesh, true) + " " + curve_groups_text(mesh) +
                              ", none named open...: the whole boundary is land (name the "
                              "open ones with --open-groups)");
  }
  return source;
}

// A raster INPUT is read whole, or under --bbox or --clip: the vector selections have
// nothing to select, and its domain is set by --zmin and --zmax.
void check_raster_selection(const FrontEndOptions& options) {
  const ReadParams& read = options.read;
  const std::pair<bool, const char*> selections[] = {{!read.layer.empty(), "--layer"},
                                                     {!read.where.empty(), "--where"},
                                                     {options.kind_given, "--domain"}};
  for (const auto& [given, option] : selections)
    if (given)
      throw Error(ErrorClass::usage, "read",
                  "'" + read.path +
                      "' is a raster, whose cells in [--zmin, --zmax] are the "
                      "domain: " +
                      option + " is for a vector file's polygons");
}

// --domain sea with --where (or --each): the runs of the rings of the layer's other
// polygons that come near the selected ones (in the source CRS; a segment across the
// antimeridian, meant the short way, ends a run), each with the index of its polygon in
// `polygon_of`. Sea areas that border the one meshed meet it in open water: its edges on
// their rings are open, its coast land. Only the runs near it are kept: Russia's ring,
// next to Azerbaijan, holds 10,000 points round half the globe.
std::vector<std::vector<Point2>> neighbour_rings(const ReadParams& read, const SourceData& selected,
                                                 std::vector<int>& polygon_of) {
  std::vector<std::vector<Point2>> runs;
  std::set<long long> fids;
  std::array<double, 4> box{1e300, 1e300, -1e300, -1e300};
  for (const SourcePolygon& p : selected.polygons) {
    fids.insert(p.fid);
    for (const Ring& r : p.rings)
      for (const Point2& q : r)
        box = {std::min(box[0], q.x), std::min(box[1], q.y), std::max(box[2], q.x),
               std::max(box[3], q.y)};
  }
  if (fids.empty()) return runs;
  const double margin = 0.01 * std::hypot(box[2] - box[0], box[3] - box[1]);
  ReadParams all = read;
  all.where.clear();
  const SourceData others = read_polygons(all);
  int polygon = 0;
  for (const SourcePolygon& p : others.polygons) {
    if (fids.count(p.fid)) continue;
    std::vector<std::vector<Point2>> lines;
    for (const Ring& r : p.rings) {
      if (r.size() < 3) continue;
      std::vector<Point2> line;
      auto cut = [&lines, &line] {
        if (line.size() >= 2) lines.push_back(std::move(line));
        line.clear();
      };
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Point2 &a = r[i], &b = r[(i + 1) % r.size()];
        if (others.crs.geographic && std::abs(b.x - a.x) > 180.0) {
          cut();
          continue;
        }
        if (line.empty()) line.push_back(a);
        line.push_back(b);
      }
      cut();
    }
    std::vector<int> line_of;
    const std::size_t before = runs.size();
    keep_near_box(lines, box, margin, runs, line_of);
    if (runs.size() == before) continue;
    polygon_of.resize(runs.size(), polygon);
    ++polygon;
  }
  return runs;
}

}  // namespace

void read_clip(const FrontEndOptions& options, ReadParams& read) {
  if ((!options.clip_layer.empty() || !options.clip_where.empty()) && options.clip_path.empty())
    throw Error(ErrorClass::usage, "options", "--clip-layer and --clip-where need --clip");
  if (options.clip_path.empty()) return;
  if (read.bbox || !read.bbox_crs.empty())
    throw Error(ErrorClass::usage, "options",
                "give the area once: --bbox (with --bbox-crs) or --clip");
  read.clip =
      read_clip_area(options.clip_path, options.clip_layer, options.clip_where, read.bbox_crs);
  read.clip_name = "--clip '" + options.clip_path + "'";
}

// --exclude: its polygons in the area read (or all of them), in its CRS or else the
// INPUT's, removed from the domain (in the meshing CRS).
std::vector<Polygon> exclude_polygons(const FrontEndOptions& options, const ReadParams& read,
                                      const CrsInfo& source_crs, FrontEndResult& result) {
  const std::string what = "--exclude '" + options.exclude_path + "'";
  ReadParams rp;
  rp.path = options.exclude_path;
  rp.layer = options.exclude_layer;
  rp.where = options.exclude_where;
  rp.default_crs = source_crs.wkt;
  rp.repair = options.read.repair;
  // The area read: --bbox (in --bbox-crs, else the INPUT's CRS) or --clip (in its own).
  rp.bbox = read.bbox;
  rp.clip = read.clip;
  rp.clip_name = read.clip_name;
  rp.bbox_crs = read.bbox_crs.empty() ? source_crs.wkt : read.bbox_crs;
  if (!rp.bbox && !rp.clip) {
    // Without either, the domain's box (in the meshing CRS, 1% wider): a world file of
    // lakes or structures is read only near the domain.
    const std::array<double, 4> box = bounding_box(result.domain);
    const double margin = 0.01 * std::hypot(box[2] - box[0], box[3] - box[1]);
    rp.bbox =
        std::array<double, 4>{box[0] - margin, box[1] - margin, box[2] + margin, box[3] + margin};
    rp.bbox_crs = result.domain.crs_wkt;
  }
  rp.empty_area_ok = true;
  SourceData areas;
  try {
    areas = read_polygons(rp);
  } catch (const Error& e) {
    throw read_error_of_option(e, "--exclude");
  }
  const CrsInfo meshing_crs{result.domain.crs_wkt, result.domain.crs_name};
  // A polygon that does not transform lies far from the domain (the meshing CRS is
  // local to it: a lake at its antipode in a world file): skipped, and counted.
  const CrsTransform to_meshing(areas.crs, meshing_crs);
  std::size_t skipped = 0;
  std::vector<SourcePolygon> projected;
  for (SourcePolygon& sp : areas.polygons) {
    bool ok = true;
    for (Ring& ring : sp.rings) ok = ok && to_meshing.transform(ring) < 0;
    if (ok)
      projected.push_back(std::move(sp));
    else
      ++skipped;
  }
  if (skipped > 0)
    result.summary.warnings.push_back(
        what + ": " + std::to_string(skipped) +
        " polygon(s) cannot be transformed into the meshing CRS (far from the domain): "
        "skipped");
  areas.polygons = std::move(projected);
  ExcludeParams ep;
  ep.repair = options.read.repair;
  ep.what = what;
  const CrsTransform to_file(meshing_crs, areas.crs);
  ep.to_file = [&](const Point2& p) {
    Point2 q = p;
    return to_file.transform(q) ? q : p;
  };
  ExcludeResult r = exclude_areas(result.domain, areas.polygons, ep);
  DomainSummary& s = result.summary;
  s.exclude_path = options.exclude_path;
  s.exclude_num_polygons = r.num_polygons;
  s.exclude_num_repaired = r.num_repaired;
  s.exclude_area_removed_m2 = r.area_removed_m2;
  if (r.num_polygons == 0)
    s.warnings.push_back(what + " has no polygon in the area meshed: nothing is excluded");
  return std::move(r.removed);
}

double open_line_tolerance(const FrontEndResult& result) {
  double extent = 0.0;
  for (const auto& line : result.open_boundary_lines)
    for (const Point2& p : line) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  return result.open_boundary_tolerance_m + 1e-7 * extent;
}

FrontEndResult build_planar_domain(const FrontEndOptions& options, const Progress& progress) {
  FrontEndResult result;
  DomainSummary& s = result.summary;
  s.input_path = options.read.path;

  progress.report("read", 0.0);
  ReadParams read = options.read;
  read.empty_bbox_selection_ok = options.kind == DomainKind::water;
  read_clip(options, read);
  if ((!options.exclude_layer.empty() || !options.exclude_where.empty()) &&
      options.exclude_path.empty())
    throw Error(ErrorClass::usage, "options", "--exclude-layer and --exclude-where need --exclude");
  std::vector<std::vector<Point2>> mesh_open_lines = options.source_open_lines;
  const bool from_mesh = options.source.has_value() || is_mesh_file(read.path);
  if (!options.open_groups.empty() && (options.source || !from_mesh))
    throw Error(
        ErrorClass::usage, "options",
        "--open-groups names physical groups of a Gmsh .msh, or nodestrings of an SMS .2dm, "
        "given as INPUT");
  const bool from_raster = !options.source && !from_mesh && is_raster_input(read.path);
  if (from_raster) check_raster_selection(options);
  if ((read.zmin || read.zmax) && !from_raster && !options.source &&
      !std::filesystem::exists(read.path))
    throw Error(ErrorClass::input, "read", "'" + read.path + "' does not exist");
  if ((read.zmin || read.zmax) && !from_raster)
    throw Error(ErrorClass::usage, "options",
                "--zmin and --zmax pick the cells of a raster INPUT (a DEM): '" + read.path +
                    "' is not one");
  const DomainKind kind = from_raster ? DomainKind::water : options.kind;
  SourceData source = options.source ? *options.source
                      : from_mesh    ? read_mesh_source(options, mesh_open_lines)
                      : from_raster  ? read_raster_domain(read)
                                     : read_polygons(read);
  s.layer_name = source.layer_name;
  s.other_polygon_layers = source.other_polygon_layers;
  s.source_crs_name = source.crs.name;
  s.num_features = source.num_features;
  s.num_source_polygons = source.polygons.size();
  s.num_rings_closed = source.num_rings_closed;
  s.num_rings_dropped = source.num_rings_dropped;
  s.num_line_features = source.num_line_features;
  s.num_rings_from_lines = source.num_rings_from_lines;
  s.num_rings_joined = source.num_rings_joined;
  s.num_lines_joined = source.num_lines_joined;
  s.num_points_removed = source.num_points_removed;
  s.raster = source.raster;
  s.warnings = source.warnings;

  progress.report("select", 0.3);
  SelectParams sp;
  sp.kind = kind;
  sp.repair = options.read.repair;
  sp.source_name = options.read.path;
  SelectResult selected = select_domain(source, sp);
  s.num_repaired = selected.num_repaired;
  for (const std::string& note : selected.repair_notes) s.warnings.push_back(note);

  progress.report("project", 0.6);
  // A mesh's outline in a projected CRS in metres (a model's grid in UTM) is meshed in
  // that CRS, unless --dst-crs says otherwise: the new grid's coordinates are the old's,
  // and a depth source without a CRS of its own (the old .gr3) is read in it.
  ProjectParams project = options.project;
  if (from_mesh && project.dst_crs.empty() && source.crs.projected &&
      source.crs.linear_unit_m == 1.0)
    project.dst_crs = source.crs.wkt;
  ProjectResult projected = project_domain(selected.polygons, source.crs, project);
  result.domain = std::move(projected.domain);
  s.meshing_crs_name = result.domain.crs_name;
  s.automatic_crs = projected.local.has_value();
  s.input_crs_kept = projected.source_kept;
  s.input_crs_not_kept = projected.source_not_kept;
  if (!projected.warning.empty()) s.warnings.push_back(projected.warning);
  s.local = projected.local;
  s.meshing_crs_proj = crs_proj_string(CrsInfo{result.domain.crs_wkt, result.domain.crs_name});
  const CrsInfo meshing_crs{result.domain.crs_wkt, result.domain.crs_name};
  // Lines along the domain's edge that make it open there: --open-boundary's, or else a
  // mesh's own open boundaries (each segment on its own, as --open-boundary's).
  const bool open_lines_given = !options.open_boundary_path.empty() || !mesh_open_lines.empty();
  std::vector<int> neighbour_of;
  const std::vector<std::vector<Point2>> neighbours =
      kind == DomainKind::sea && !open_lines_given && !options.source && !from_mesh &&
              !from_raster && !read.where.empty()
          ? neighbour_rings(read, source, neighbour_of)
          : std::vector<std::vector<Point2>>();
  const std::string open_lines_name = !options.open_boundary_path.empty()
                                          ? "'" + options.open_boundary_path + "'"
                                          : "the open boundaries of '" + read.path + "'";
  if (open_lines_given) {
    s.open_boundary_path = !options.open_boundary_path.empty()
                               ? options.open_boundary_path
                               : read.path + " (its open boundaries)";
    // Each segment on its own, with its own sag: a long segment's (500 m for 150 km of a
    // line in lon/lat) would otherwise widen the tolerance round the short ones, and
    // beyond the lines' ends. The domain's boundary along a segment runs from vertex to
    // vertex of its curved image: along the whole chord where the segment is one edge of
    // the domain, along shorter chords where the domain has vertices between its ends.
    // Each such chord lies within 0.64 sag of the curve or of the whole chord (a chord
    // over a fraction f of the segment lies within f^2 sag of the curve, and its far end
    // 4 f (1 - f) sag from the whole chord): 0.7 sag is enough.
    ProjectedLines p;
    if (!options.open_boundary_path.empty()) {
      p = read_projected_lines(options.open_boundary_path, options.open_boundary_layer,
                               "open boundary", source.crs, meshing_crs, true);
    } else {
      p = project_lines(mesh_open_lines, source.crs, meshing_crs, true);
      if (p.failed_line >= 0)
        throw Error(ErrorClass::crs, "open boundary",
                    "'" + read.path + "': a node of open boundary " +
                        std::to_string(p.failed_line + 1) +
                        " cannot be transformed into the meshing CRS");
      p.num_source_lines = mesh_open_lines.size();
    }
    s.open_boundary_num_lines = p.num_source_lines;
    result.open_boundary_lines = p.lines;
    result.open_boundary_line_group = p.line_of;
    for (double sag : p.sag_m) result.open_boundary_slack_m.push_back(0.7 * sag);
    result.open_boundary_chord_share = 0.2;
  } else if (!neighbours.empty()) {
    // The other polygons' rings, and the bbox's (or area's) when there is one, each
    // polygon and the bbox a group of its own (a segment each), as --open-boundary's.
    std::vector<std::vector<Point2>> lines = neighbours;
    std::vector<int> group = neighbour_of;
    const int num_neighbours = neighbour_of.back() + 1;
    if (source.bbox_ring) {
      lines.push_back(*source.bbox_ring);
      lines.back().push_back(lines.back().front());
      group.push_back(num_neighbours);
    }
    const ProjectedLines p = project_lines(lines, source.crs, meshing_crs, true);
    if (p.failed_line >= 0)
      throw Error(ErrorClass::crs, "open boundary",
                  "'" + read.path +
                      "': a point of a polygon next to the selection cannot be "
                      "transformed into the meshing CRS");
    s.open_boundary_path = read.path + " (its " + std::to_string(num_neighbours) +
                           " other polygon(s) next to the selection" +
                           (source.bbox_ring ? std::string(", and the area's edge)") : ")");
    s.open_boundary_num_lines = lines.size();
    result.open_boundary_lines = p.lines;
    for (int l : p.line_of) result.open_boundary_line_group.push_back(group[l]);
    for (double sag : p.sag_m) result.open_boundary_slack_m.push_back(0.7 * sag);
    result.open_boundary_chord_share = 0.2;
  } else if ((kind == DomainKind::water || kind == DomainKind::sea) && source.bbox_ring) {
    Ring box = *source.bbox_ring;
    box.push_back(box.front());
    const ProjectedLines p = project_lines({box}, source.crs, meshing_crs, false);
    if (p.failed_line < 0) {
      result.open_boundary_lines = p.lines;
      result.open_boundary_line_group = p.line_of;
      result.open_boundary_tolerance_m =
          2.0 * p.sag_m[0];  // the simplification tolerance added below
    }
  }

  if (!options.align_path.empty()) {
    s.align_path = options.align_path;
    const ProjectedLines p = read_projected_lines(options.align_path, options.align_layer, "align",
                                                  source.crs, meshing_crs, false);
    s.align_num_lines = p.num_source_lines;
    const std::array<double, 4> box = bounding_box(result.domain);
    keep_near_box(p.lines, box, 0.01 * std::hypot(box[2] - box[0], box[3] - box[1]),
                  result.align_lines, result.align_line_of);
  }

  if (!options.embed_points_path.empty()) {
    const std::string& path = options.embed_points_path;
    s.embed_points_path = path;
    const std::string& named = options.embed_points_name_field;
    PointLayer layer = read_point_layer(
        path, "--embed-points", false, "", "", std::numeric_limits<std::size_t>::max(),
        {named.empty() ? "name" : named, "--embed-points-name", !named.empty()});
    // Each point is a station the user placed: one that cannot be read is an error.
    if (layer.num_without_point > 0)
      throw Error(ErrorClass::input, "read",
                  "--embed-points '" + path + "': " + std::to_string(layer.num_without_point) +
                      " feature(s) without a point, the first feature " +
                      std::to_string(layer.first_without_point) +
                      " (coordinates that are not numbers, or empty)" +
                      (layer.gdal_message.empty() ? "" : ": " + layer.gdal_message));
    if (layer.points.empty())
      throw Error(ErrorClass::input, "read", "--embed-points '" + path + "': holds no point");
    const CrsInfo from =
        layer.crs.empty() ? source.crs : parse_crs(layer.crs, "'" + path + "' (its CRS)");
    const long failed = CrsTransform(from, meshing_crs).transform(layer.points);
    if (failed >= 0)
      throw Error(ErrorClass::crs, "read",
                  "--embed-points '" + path + "': point " + std::to_string(failed + 1) +
                      " cannot be transformed into the meshing CRS");
    s.embed_points_read = layer.points.size();
    result.embed_points = std::move(layer.points);
    result.embed_point_name = std::move(layer.names);
  }

  const std::vector<Polygon> excluded = options.exclude_path.empty()
                                            ? std::vector<Polygon>()
                                            : exclude_polygons(options, read, source.crs, result);

  progress.report("clean", 0.7);
  const std::shared_ptr<const MapScale> scale =
      options.map_scale_for_domain ? options.map_scale_for_domain(result.domain) : nullptr;
  double h = options.target_size_for_domain
                 ? options.target_size_for_domain(result.domain, scale.get())
                 : options.target_size_m;
  // A raster knows nothing smaller than its cells: islands, holes and notches under a
  // cell are its noise, cleaned as such.
  if (source.raster) h = std::max(h, source.raster->cell_size_m);
  s.target_size_m = h;
  CleanParams cp;
  cp.largest = options.largest;
  cp.min_island_area_m2 = options.min_island_area_m2.value_or(h > 0 ? h * h : 0.0);
  cp.min_hole_area_m2 = cp.min_island_area_m2;
  cp.min_island_area_given = options.min_island_area_m2.has_value();
  if (scale)
    cp.area_factor = [scale, k_min = scale->min()](const Point2& p) {
      const double r = k_min / scale->at(p);
      return r * r;
    };
  if (cp.min_island_area_m2 < 0)
    throw Error(ErrorClass::usage, "clean", "--min-island-area must not be negative");
  s.min_island_area_m2 = cp.min_island_area_m2;
  s.dropped = clean_domain(result.domain, cp);

  progress.report("simplify", 0.8);
  SimplifyParams simp;
  // A raster's contour steps from cell to cell: by default it is simplified by a cell.
  simp.tolerance_m = options.simplify_m.value_or(source.raster ? source.raster->cell_size_m
                                                 : h > 0       ? 0.25 * h
                                                               : 0.0);
  if (simp.tolerance_m < 0) throw Error(ErrorClass::usage, "simplify", "--simplify must not be negative");
  s.simplify_m = simp.tolerance_m;
  // Parts of the boundary are kept as far apart as the tolerance (or as they were):
  // otherwise a channel narrower than twice the tolerance could close to a crack.
  simp.clearance_m = options.simplify_clearance_m.value_or(simp.tolerance_m);
  if (simp.clearance_m < 0)
    throw Error(ErrorClass::usage, "simplify", "the simplification's clearance must not be negative");
  const SimplifyResult sr = simplify_domain(result.domain, simp);
  s.num_vertices_before = sr.num_vertices_before;
  s.num_vertices_after = sr.num_vertices_after;

  // Rings touching at a point (not for the mesher; GEOS's overlays refuse a ring that
  // touches itself, so the narrow features would pass such a domain unchanged: the
  // Caribbean's water at 1:10m): cut apart there, before the narrow features and again
  // after them.
  std::size_t pinches_cut = 0;
  const double pinch_gap =
      simp.tolerance_m > 0 ? simp.tolerance_m : 1e-4 * std::sqrt(area(result.domain));
  auto cut_pinches = [&] {
    std::size_t pinches = pinch_points(result.domain).size();
    if (pinches == 0) return;
    // Boundaries that coincide (pieces of one land mass cut at the antimeridian, the
    // sides of a bbox round every longitude) are merged, not cut apart.
    const std::size_t pieces = result.domain.polygons.size();
    if (merge_shared_boundaries(result.domain)) {
      s.warnings.push_back("boundaries that coincide once projected were merged (" +
                           std::to_string(pieces) + " polygon(s) before, " +
                           std::to_string(result.domain.polygons.size()) + " after)");
      pinches = pinch_points(result.domain).size();
    }
    // A cut can leave two of its pieces touching at a point (slivers between a coast
    // and the bbox edge: the Arctic's water at 66 N): those are cut in turn.
    constexpr int kCutRounds = 3;
    auto cut_rounds = [&] {
      for (int round = 0; round < kCutRounds && pinches > 0; ++round) {
        separate_rings(result.domain, pinch_gap);
        pinches_cut += pinches;
        pinches = pinch_points(result.domain).size();
      }
    };
    cut_rounds();
    if (pinches == 0) return;
    // Still touching: slits whose sides the cuts cannot part (two polygons that should
    // share a side, a corner a tenth of a millimetre off). Closed at a hundredth of the
    // cut's width, then cut again.
    close_hairline_gaps(result.domain, 0.01 * pinch_gap);
    pinches = pinch_points(result.domain).size();
    if (pinches > 0) cut_rounds();
    if (pinches == 0) {
      s.warnings.push_back("slits narrower than " + printf_string("%.3g", 0.02 * pinch_gap) +
                           " m where rings touched (polygons that miss each other by a hair) "
                           "were closed");
      return;
    }
    const std::vector<Point2> left = pinch_points(result.domain);
    throw Error(ErrorClass::input, "simplify",
                "rings still touch after cutting them apart (" + std::to_string(left.size()) +
                    " place(s), the first near " +
                    format_meshing_place(left[0], result.domain.crs_wkt) + ")");
  };
  cut_pinches();

  progress.report("narrow features", 0.9);
  NarrowParams np;
  np.min_width_m = options.min_width_m.value_or(h > 0 ? 0.25 * h : 0.0);
  if (np.min_width_m < 0) throw Error(ErrorClass::usage, "narrow features", "--min-width must not be negative");
  s.min_width_m = np.min_width_m;
  // The opening may cut off small pieces, and the offsets leave vertices closer together
  // than the simplification would: both are cleaned as before. Simplifying again can
  // make a new narrow feature (a bay filled up to its mouth simplifies to a thin wedge:
  // the Rade de Brest at 15 km), so the three steps repeat while the narrow-feature
  // step changes more than min_width^2 of area (slivers the offsets alone move are far
  // smaller), a few rounds at most.
  constexpr int kNarrowRounds = 3;
  auto clean_and_simplify_again = [&] {
    const CleanResult again = clean_domain(result.domain, cp);
    s.dropped.num_islands_dropped += again.num_islands_dropped;
    s.dropped.num_holes_dropped += again.num_holes_dropped;
    s.num_vertices_after = simplify_domain(result.domain, simp).num_vertices_after;
  };
  auto narrow_rounds = [&](bool first) {
    for (int round = 0; round < kNarrowRounds; ++round) {
      const NarrowResult n = remove_narrow_features(result.domain, np);
      if (round == 0 && first)
        s.narrow = n;
      else
        s.narrow.add(n);
      if (!n.changed) break;
      const double moved = n.area_removed_m2 + n.area_added_m2;
      clean_and_simplify_again();
      if (moved < np.min_width_m * np.min_width_m) break;
    }
  };
  narrow_rounds(true);
  // Pieces kept for the topology that are far narrower than any quad (two islands or
  // tiles a centimetre apart, a strip of land a few millimetres wide between a lake and
  // the sea) are digitising artefacts: the background mesh would refine down to their
  // width (a gap of 1 cm: 1.1 million vertices and 5 minutes for 2,400 quads) and the
  // quads across them be needles (a strip 1/400 of the quads wide: an aspect ratio of
  // thousands). Those are closed or cut out whatever that does to the topology, and the
  // narrow features run again (filling round the joins just made).
  if (options.hairline_m && *options.hairline_m < 0)
    throw Error(ErrorClass::usage, "narrow features", "--hairline must not be negative");
  NarrowParams hairline = np;
  hairline.min_width_m = options.hairline_m.value_or(kHairlineShare * np.min_width_m);
  s.hairline_m = hairline.min_width_m;
  if (hairline.min_width_m > 0 && s.narrow.num_pieces_kept > 0) {
    const NarrowResult n = close_hairlines(result.domain, hairline, s.narrow.kept);
    if (n.changed) {
      s.narrow.add(n);
      s.warnings.push_back(printf_string(
          "%zu gap(s) or strip(s) narrower than --hairline (%.3g m) closed or cut out although "
          "that joins or cuts components or holes (the largest near (%.10g, %.10g) in the "
          "meshing CRS): so narrow, they are taken for digitising artefacts; --hairline 0 "
          "keeps them",
          n.num_pieces, hairline.min_width_m, n.largest_changed.at.x, n.largest_changed.at.y));
      clean_and_simplify_again();
      narrow_rounds(false);
    }
  }
  // Parts of the domain narrower than --min-width kept, at least a quad long and narrower
  // than the width on average (a strait, a land bridge; not the gaps kept between parts
  // of it, which need nothing of the quads, nor the tip of a wedge, nor a large piece
  // with a narrow neck): said, with the narrowest.
  const NarrowPlace* narrowest = nullptr;
  std::vector<NarrowPlace> strips;
  for (const NarrowResult::Kept& k : s.narrow.kept) {
    if (!k.cut || perimeter(k.piece.outer) < 8 * np.min_width_m) continue;
    const NarrowPlace place = place_of(k.piece);
    if (place.width_m < np.min_width_m) strips.push_back(place);
  }
  for (const NarrowPlace& p : strips)
    if (!narrowest || p.width_m < narrowest->width_m) narrowest = &p;
  if (narrowest)
    s.warnings.push_back(printf_string(
        "%zu part(s) of the domain narrower than --min-width (%.4g m) kept, since cutting them "
        "out would cut components or open holes (straits, isthmuses, land bridges); the "
        "narrowest near %s, about %.4g m wide: quads there may be long and narrow; smaller "
        "sizes there (--refine, --hmin) give them better shapes, and --hairline above its "
        "width cuts it out",
        strips.size(), np.min_width_m,
        format_meshing_place(narrowest->at, result.domain.crs_wkt).c_str(), narrowest->width_m));
  cut_pinches();
  // Last, tips sharper than a quad's corner may be (after the simplification, which can
  // sharpen them), cut back to min_width wide.
  SpikeParams spikes;
  spikes.min_width_m = np.min_width_m;
  s.spikes = cut_spike_tips(result.domain, spikes);
  // The cuts round pinches and tips can leave pieces under the islands' and holes' least
  // area (a triangle of 0.3 m2 where a spit was cut apart from its coast): dropped, as
  // the first cleaning drops such pieces; the tiling cannot cover them.
  const CleanResult last = clean_domain(result.domain, cp);
  s.dropped.num_islands_dropped += last.num_islands_dropped;
  s.dropped.num_holes_dropped += last.num_holes_dropped;
  if (pinches_cut > 0) {
    char width[32];
    std::snprintf(width, sizeof width, "%.3g", 2 * pinch_gap);
    s.warnings.push_back(std::to_string(pinches_cut) +
                         " point(s) where rings touched were cut apart (a " + width +
                         " m wide gap each)");
  }
  if (!result.open_boundary_lines.empty())
    result.open_boundary_tolerance_m += 1.01 * simp.tolerance_m;
  if (open_lines_given || !neighbours.empty()) {
    // Lines that follow none of the domain's boundary would leave it all land: an
    // ocean model without a sea boundary. The length they follow: that of the boundary's
    // open parts (open_parts). (Polygons next to a sea area may touch it at points only.)
    add_domain_chords(result, source.crs, meshing_crs);
    const double tolerance = open_line_tolerance(result);
    for (const auto& part : open_parts(result)) s.open_boundary_length_m += polyline_length(part);
    if (!(s.open_boundary_length_m > 0.0) && open_lines_given) {
      char text[32];
      std::snprintf(text, sizeof text, "%.4g", tolerance);
      throw Error(ErrorClass::input, "open boundary",
                  open_lines_name +
                      ": the lines follow none of the domain's boundary (none of it lies within " +
                      text +
                      " m of them); draw them along the domain's edge (snapped to its vertices)");
    }
  }

  if (!result.open_boundary_lines.empty()) result.open_boundary_parts = open_parts(result);
  s.num_open_parts = result.open_boundary_parts.size();
  for (const auto& part : result.open_boundary_parts)
    s.open_parts_length_m += polyline_length(part);
  // Also where the layer's other polygons lie near the selection but border it nowhere
  // (Madagascar's neighbours at 1:10m), or the bbox holds it whole.
  if (kind == DomainKind::sea && !open_lines_given && !(s.open_parts_length_m > 0.0))
    s.warnings.push_back(
        "--domain sea: the polygons' edge meets neither the edge of --bbox or --clip nor "
        "(with --where or --each) another polygon of the layer: all of it is land; mark its "
        "open parts with --open-boundary");
  if (!s.embed_points_path.empty()) {
    // Inside the domain, or outside it within the target size of its boundary: the
    // meshing puts those near the coast on it (EmbedParams::point_coast_share).
    std::vector<Point2> kept;
    std::vector<std::string> kept_names;
    std::string first_far;  // the first few left out, by name or number
    std::size_t num_listed = 0;
    for (std::size_t k = 0; k < result.embed_points.size(); ++k) {
      const Point2& p = result.embed_points[k];
      const bool inside = domain_contains(result.domain, p);
      if (!inside &&
          !(s.target_size_m > 0 && distance_to_boundary(result.domain, p) <= s.target_size_m)) {
        if (num_listed < 5)
          first_far += (first_far.empty() ? "" : ", ") +
                       (result.embed_point_name.empty() || result.embed_point_name[k].empty()
                            ? "point " + std::to_string(k + 1)
                            : "'" + result.embed_point_name[k] + "'");
        else if (num_listed == 5)
          first_far += ", ...";
        ++num_listed;
        continue;
      }
      kept.push_back(p);
      if (!result.embed_point_name.empty()) kept_names.push_back(result.embed_point_name[k]);
      result.embed_point_number.push_back(static_cast<int>(k + 1));
      if (inside) ++s.embed_points_inside;
    }
    const std::size_t far = s.embed_points_read - kept.size();
    const std::string outside =
        std::to_string(far) + " of the " + std::to_string(s.embed_points_read) + " points of '" +
        s.embed_points_path + "' lie outside the domain" +
        (s.target_size_m > 0 ? printf_string(", farther than %.0f m from it", s.target_size_m)
                             : std::string()) +
        (far > 0 ? " (" + first_far + ")" : std::string());
    if (kept.empty() && !options.align_optional)
      throw Error(ErrorClass::input, "read", "--embed-points: " + outside);
    if (far > 0) s.warnings.push_back("--embed-points: " + outside + ": they get no vertex");
    result.embed_points = std::move(kept);
    result.embed_point_name = std::move(kept_names);
  }
  if (!excluded.empty()) {
    // The cleaning and simplification may give some of it back: say so where they do.
    const ExcludedMeshed back = excluded_area_meshed(result.domain, excluded);
    s.exclude_area_meshed_m2 = back.area_m2;
    s.exclude_num_meshed = back.num_mostly;
    if (back.num_mostly > 0)
      s.warnings.push_back(printf_string(
          "--exclude '%s': %zu of its %zu area(s) lie mostly in the domain after all (%.4g km2 "
          "of the %.4g removed): holes under --min-island-area (%.4g m2) are dropped and "
          "pieces narrower than --min-width (%.4g m) filled in; lower those, or the sizes there",
          options.exclude_path.c_str(), back.num_mostly, back.num_areas, back.area_m2 / 1e6,
          s.exclude_area_removed_m2 / 1e6, s.min_island_area_m2, s.min_width_m));
  }
  s.num_components = result.domain.polygons.size();
  s.num_holes = num_holes(result.domain);
  s.num_rings = s.num_components + s.num_holes;
  s.area_m2 = area(result.domain);
  s.perimeter_m = perimeter(result.domain);
  if (options.warn_distortion && s.local && s.local->max_distance_km > 2000.0) {
    // The stereographic scale at angular distance c from the centre is k0 / cos^2(c/2):
    // 1.025 times the centre's at 2,000 km (lengths 1.2% off either way), 100 times near
    // the antipode.
    const double half_c = 0.5 * s.local->max_distance_km / 6371.0088;
    s.warnings.push_back(printf_string(
        "the domain spans %.0f km from its centre: the automatic projection's lengths there "
        "are %.3g times those at its centre; consider --dst-crs",
        s.local->max_distance_km, 1.0 / (std::cos(half_c) * std::cos(half_c))));
  }
  progress.report("done", 1.0);
  return result;
}

}  // namespace isoquad
