#include "gis/mesh_outline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>
#include <unordered_map>

#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/rings_from_lines.h"

namespace isoquad {

namespace {

struct Side {
  int from = 0, to = 0;  // as the first element that has it runs it
  int uses = 0;
};

// The angle turned clockwise from direction u to direction v, in (0, 2 pi].
double clockwise_turn(const Point2& u, const Point2& v) {
  double a = std::atan2(u.y, u.x) - std::atan2(v.y, v.x);
  while (a <= 0) a += 2 * M_PI;
  while (a > 2 * M_PI) a -= 2 * M_PI;
  return a;
}

// A closed walk that passes a node twice (two holes touching there: the walk that keeps
// to the domain's side goes from one into the other) as the simple loops it is made of,
// each cut off where the walk comes back to a node.
void split_at_repeated_nodes(const std::vector<int>& walk, std::vector<std::vector<int>>& loops) {
  std::vector<int> stack;
  std::unordered_map<int, std::size_t> at;  // node -> its place in the stack
  std::vector<std::vector<int>> cut;
  for (int v : walk) {
    const auto it = at.find(v);
    if (it == at.end()) {
      at.emplace(v, stack.size());
      stack.push_back(v);
      continue;
    }
    std::vector<int> loop(stack.begin() + static_cast<std::ptrdiff_t>(it->second), stack.end());
    for (std::size_t i = 1; i < loop.size(); ++i) at.erase(loop[i]);
    stack.resize(it->second + 1);
    cut.push_back(std::move(loop));
  }
  loops.push_back(std::move(stack));
  for (auto& loop : cut) loops.push_back(std::move(loop));
}

// In longitudes, whether an element has a side across more than 180 degrees: the mesh
// crosses the cut of its longitudes (a grid round the globe, which no choice of the
// cut avoids, or one across the antimeridian written in [-180, 180)).
bool crosses_the_cut(const ReadMesh& mesh) {
  auto across = [&](const int* v, int k) {
    for (int i = 0; i < k; ++i)
      if (std::abs(mesh.points[v[i]].x - mesh.points[v[(i + 1) % k]].x) > 180.0) return true;
    return false;
  };
  for (const auto& q : mesh.quads)
    if (across(q.data(), 4)) return true;
  for (const auto& t : mesh.triangles)
    if (across(t.data(), 3)) return true;
  return false;
}

}  // namespace

std::vector<std::vector<int>> mesh_outline(const std::vector<Point2>& points,
                                           const std::vector<std::array<int, 4>>& quads,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::string& name,
                                           const std::vector<long long>& point_ids) {
  const std::string file = "'" + name + "'";
  const auto node = [&point_ids](int k) {
    return std::to_string(file_number(point_ids, static_cast<std::size_t>(k)));
  };
  if (quads.empty() && triangles.empty())
    throw Error(ErrorClass::input, "quality", file + " has no elements");
  const auto n = static_cast<std::uint64_t>(points.size());
  std::unordered_map<std::uint64_t, Side> sides;
  std::vector<std::uint64_t> order;  // the sides' keys as first met
  double orientation = 0;            // counter-clockwise elements minus clockwise ones
  auto add = [&](const int* v, int k) {
    double twice_area = 0;
    for (int i = 0; i < k; ++i) {
      const Point2 &a = points[v[i]], &b = points[v[(i + 1) % k]];
      twice_area += a.x * b.y - a.y * b.x;
      const int lo = std::min(v[i], v[(i + 1) % k]), hi = std::max(v[i], v[(i + 1) % k]);
      const std::uint64_t key = static_cast<std::uint64_t>(lo) * n + static_cast<std::uint64_t>(hi);
      auto [it, added] = sides.try_emplace(key, Side{v[i], v[(i + 1) % k], 0});
      if (added) order.push_back(key);
      if (++it->second.uses > 2)
        throw Error(ErrorClass::input, "quality",
                    file + ": the edge between nodes " + node(lo) + " and " + node(hi) +
                        " is a side of three or more elements");
    }
    orientation += twice_area > 0 ? 1 : twice_area < 0 ? -1 : 0;
  };
  for (const auto& q : quads) add(q.data(), 4);
  for (const auto& t : triangles) add(t.data(), 3);

  // The boundary's edges leaving each node, domain on the left.
  std::vector<std::vector<int>> out(points.size());
  std::vector<std::array<int, 2>> edges;
  for (std::uint64_t key : order) {
    const Side& s = sides.at(key);
    if (s.uses != 1) continue;
    const std::array<int, 2> e =
        orientation >= 0 ? std::array<int, 2>{s.from, s.to} : std::array<int, 2>{s.to, s.from};
    out[e[0]].push_back(static_cast<int>(edges.size()));
    edges.push_back(e);
  }
  std::vector<char> used(edges.size(), 0);
  std::vector<std::vector<int>> loops;
  for (std::size_t start_node = 0; start_node < out.size(); ++start_node) {
    for (int first : out[start_node]) {
      if (used[first]) continue;
      std::vector<int> loop;
      int e = first;
      for (;;) {
        used[e] = 1;
        loop.push_back(edges[e][0]);
        const int from = edges[e][0], at = edges[e][1];
        int next = -1;
        double best = 0;
        for (int c : out[at]) {
          if (used[c] && c != first) continue;
          const Point2 &p = points[at], &back = points[from], &ahead = points[edges[c][1]];
          const double turn =
              clockwise_turn({back.x - p.x, back.y - p.y}, {ahead.x - p.x, ahead.y - p.y});
          if (next < 0 || turn < best) next = c, best = turn;
        }
        if (next < 0)
          throw Error(ErrorClass::input, "quality",
                      file + ": its boundary does not close at node " + node(at) +
                          " (elements of both orientations meet there?)");
        if (next == first) break;
        e = next;
      }
      split_at_repeated_nodes(loop, loops);
    }
  }
  return loops;
}

SourceData outline_source(const ReadMesh& mesh, const std::string& path,
                          const std::string& crs_text, const std::string& option,
                          std::vector<Point2>* nodes) {
  const std::string given = !crs_text.empty() ? crs_text : mesh.crs;
  if (given.empty()) {
    // SCHISM's grid in lon/lat beside it: the same nodes and elements, with a CRS.
    std::filesystem::path ll(path);
    ll.replace_extension(".ll");
    std::error_code ec;
    const bool has_ll = mesh.format == "gr3" && std::filesystem::exists(ll, ec);
    throw Error(ErrorClass::crs, "read",
                "'" + path + "' does not say its CRS: its outline is the domain, so give the " +
                    "CRS of its coordinates with " + option +
                    " (EPSG:4326 for longitudes and latitudes, or the projected CRS it was made "
                    "in, e.g. EPSG:32631; for isoquad's grids the summary's meshing CRS, the "
                    "report's meshing_crs_proj)" +
                    (has_ll ? ", or give '" + ll.string() +
                                  "' instead: the same grid in longitudes and latitudes"
                            : std::string()));
  }
  SourceData source;
  source.crs = parse_crs(given, crs_text.empty() ? "'" + path + "' (its projection)" : option);
  // Metres read as degrees (a grid in UTM given --src-crs EPSG:4326): said as for polygons.
  if (source.crs.geographic)
    for (std::size_t k = 0; k < mesh.points.size(); ++k) {
      const Point2& q = mesh.points[k];
      if (std::abs(q.y) > 90.0 || q.x < -360.0 || q.x > 360.0)
        throw Error(ErrorClass::crs, "read",
                    "'" + path + "': node " + std::to_string(file_number(mesh.point_ids, k)) + " " +
                        format_point(q) + " is outside the valid range of '" + source.crs.name +
                        "' (longitude -360..360, latitude -90..90); are the coordinates in "
                        "another CRS? Give it with " +
                        option);
    }
  // A band round the globe is an annulus only round a pole.
  std::vector<Point2> points = mesh.points;
  if (source.crs.geographic && crosses_the_cut(mesh)) {
    const LocalProjection local = choose_local_projection(geographic_base(source.crs), points);
    const long failed = CrsTransform(source.crs, local.crs).transform(points);
    if (failed >= 0)
      throw Error(
          ErrorClass::crs, "read",
          "'" + path + "': node " +
              std::to_string(file_number(mesh.point_ids, static_cast<std::size_t>(failed))) + " " +
              format_point(mesh.points[static_cast<std::size_t>(failed)]) +
              " cannot be transformed to '" + local.crs.name + "'");
    source.crs = local.crs;
  }
  const std::vector<std::vector<int>> loops =
      mesh_outline(points, mesh.quads, mesh.triangles, path, mesh.point_ids);
  std::vector<SourceLine> lines;
  for (const std::vector<int>& loop : loops) {
    SourceLine line;
    line.fid = static_cast<long long>(lines.size());
    for (int v : loop) line.points.push_back(points[v]);
    line.points.push_back(line.points.front());
    lines.push_back(std::move(line));
  }
  try {
    source.polygons = rings_from_lines(lines, source.crs.geographic ? "degrees" : "m").polygons;
  } catch (const LinesError& e) {
    throw Error(ErrorClass::input, "read", "'" + path + "': its outline: " + e.what());
  }
  if (nodes) *nodes = std::move(points);
  source.layer_name = "its outline";
  source.num_features = loops.size();
  return source;
}

MeshDefects find_mesh_defects(const ReadMesh& mesh) {
  const std::vector<Point2>& points = mesh.points;
  const std::vector<long long>& point_ids = mesh.point_ids;
  MeshDefects d;
  const auto number = [&point_ids](int k) {
    return file_number(point_ids, static_cast<std::size_t>(k));
  };
  std::vector<char> used(points.size(), 0);
  std::unordered_map<std::uint64_t, int> uses;  // a side's key -> its elements
  const auto n = static_cast<std::uint64_t>(points.size());
  const auto add = [&](const int* v, int k) {
    for (int i = 0; i < k; ++i) {
      used[v[i]] = 1;
      const int lo = std::min(v[i], v[(i + 1) % k]), hi = std::max(v[i], v[(i + 1) % k]);
      if (++uses[static_cast<std::uint64_t>(lo) * n + static_cast<std::uint64_t>(hi)] == 3 &&
          d.num_overused_sides++ == 0)
        d.first_overused = {number(lo), number(hi)};
    }
  };
  // Each element's way round: +1 counter-clockwise, -1 clockwise, 0 flat.
  std::vector<int> way;
  const auto way_round = [&points](const int* v, int k) {
    double area = 0;  // the fan of triangles from the first corner
    for (int i = 1; i + 1 < k; ++i)
      area += signed_area(points[v[0]], points[v[i]], points[v[i + 1]]);
    return area > 0 ? 1 : area < 0 ? -1 : 0;
  };
  for (const auto& q : mesh.quads) add(q.data(), 4), way.push_back(way_round(q.data(), 4));
  for (const auto& t : mesh.triangles) add(t.data(), 3), way.push_back(way_round(t.data(), 3));
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!used[k] && d.num_unused_nodes++ == 0) d.first_unused = number(static_cast<int>(k));
  const long long balance = std::accumulate(way.begin(), way.end(), 0LL);
  const int most = balance >= 0 ? 1 : -1;
  d.num_elements = way.size();
  const std::size_t nq = mesh.quads.size();
  const auto element = [&](std::size_t e) {
    return e < nq ? "quad " + std::to_string(file_number(mesh.quad_ids, e))
                  : "triangle " + std::to_string(file_number(mesh.triangle_ids, e - nq));
  };
  // A quad whose opposite sides cross (a bow-tie): each diagonal leaves its two
  // triangles turning opposite ways.
  const auto crosses_itself = [&points](const std::array<int, 4>& q) {
    const auto turn = [&points](int a, int b, int c) {
      return signed_area(points[a], points[b], points[c]);
    };
    return turn(q[0], q[1], q[2]) * turn(q[0], q[2], q[3]) < 0 &&
           turn(q[0], q[1], q[3]) * turn(q[1], q[2], q[3]) < 0;
  };
  // Elements given twice: the same nodes, in any order. Each element as its sorted nodes
  // (a triangle's fourth -1) and its index, sorted, so that the copies fall together.
  std::vector<std::array<long long, 5>> keyed;
  keyed.reserve(way.size());
  for (std::size_t e = 0; e < way.size(); ++e) {
    std::array<long long, 5> key{-1, -1, -1, -1, static_cast<long long>(e)};
    const int* v = e < nq ? mesh.quads[e].data() : mesh.triangles[e - nq].data();
    for (int i = 0; i < (e < nq ? 4 : 3); ++i) key[i] = v[i];
    std::sort(key.begin(), key.begin() + 4);
    keyed.push_back(key);
  }
  std::sort(keyed.begin(), keyed.end());
  std::size_t first_copy = way.size(), its_original = 0;
  for (std::size_t i = 1, group = 0; i < keyed.size(); ++i) {
    if (!std::equal(keyed[i].begin(), keyed[i].begin() + 4, keyed[group].begin())) {
      group = i;
      continue;
    }
    ++d.num_duplicate_elements;
    const auto e = static_cast<std::size_t>(keyed[i][4]);
    if (e < first_copy) first_copy = e, its_original = static_cast<std::size_t>(keyed[group][4]);
  }
  if (d.num_duplicate_elements > 0)
    d.first_duplicate = element(first_copy) + " (as " + element(its_original) + ")";
  for (std::size_t e = 0; e < way.size(); ++e) {
    if ((way[e] == 0 || (e < nq && crosses_itself(mesh.quads[e]))) && d.num_degenerate++ == 0)
      d.first_degenerate = element(e);
    if (way[e] == -most && d.num_reversed++ == 0) d.first_reversed = element(e);
  }
  // Coincident nodes: swept in the order of x, each against the later ones within the
  // tolerance in x.
  if (points.empty()) return d;
  double x0 = points[0].x, x1 = x0, y0 = points[0].y, y1 = y0;
  for (const Point2& p : points)
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  d.coincident_tolerance = 1e-9 * std::max(x1 - x0, y1 - y0);
  std::vector<int> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::sort(order.begin(), order.end(), [&points](int a, int b) {
    return points[a].x < points[b].x || (points[a].x == points[b].x && a < b);
  });
  std::vector<char> counted(points.size(), 0);
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1;
         j < order.size() && points[order[j]].x - points[order[i]].x <= d.coincident_tolerance;
         ++j) {
      const int a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
      if (counted[b] || std::abs(points[a].y - points[b].y) > d.coincident_tolerance) continue;
      counted[b] = 1;
      if (d.num_coincident_nodes++ == 0) d.first_coincident = {number(a), number(b)};
    }
  return d;
}

std::vector<std::string> mesh_defect_warnings(const MeshDefects& d) {
  std::vector<std::string> out;
  if (d.num_duplicate_elements > 0)
    out.push_back(std::to_string(d.num_duplicate_elements) +
                  " element(s) given twice, on the same nodes (the first: " + d.first_duplicate +
                  "); the mesh's area and coast are not those of a valid mesh");
  if (d.num_overused_sides > 0)
    out.push_back(std::to_string(d.num_overused_sides) +
                  " side(s) of three or more elements (the first between nodes " +
                  std::to_string(d.first_overused[0]) + " and " +
                  std::to_string(d.first_overused[1]) +
                  "): an element given twice, or elements that overlap; the mesh's area and "
                  "coast are not those of a valid mesh");
  if (d.num_degenerate > 0)
    out.push_back(
        std::to_string(d.num_degenerate) +
        " element(s) without area or crossing themselves (the first: " + d.first_degenerate +
        "): flat, or a quad whose opposite sides cross (a bow-tie); they count as "
        "inverted");
  if (d.num_reversed > 0)
    out.push_back(
        std::to_string(d.num_reversed) + " of its " + std::to_string(d.num_elements) +
        " elements run round the other way from the rest (the first: " + d.first_reversed +
        "): listed the other way round, or folded over their neighbours; they count "
        "as inverted");
  if (d.num_coincident_nodes > 0)
    out.push_back(printf_string(
        "%zu node(s) at the place of an earlier one (the first: nodes %lld and %lld, within "
        "%.3g of each other): the elements on either side are not joined there (nodes left "
        "unmerged, a crack), and their sides count as boundary",
        d.num_coincident_nodes, d.first_coincident[0], d.first_coincident[1],
        d.coincident_tolerance));
  if (d.num_unused_nodes > 0)
    out.push_back(std::to_string(d.num_unused_nodes) + " node(s) in no element (the first: node " +
                  std::to_string(d.first_unused) +
                  "): counted among the vertices, but no model computes on them");
  return out;
}

}  // namespace isoquad
