#include "tiling/repair_tiling.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "tiling/tile_boundary.h"

namespace isoquad {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

// Counter-clockwise angle from direction (rx, ry) to (x, y), in [0, 2 pi).
double angle_from(double rx, double ry, double x, double y) {
  double a = std::atan2(rx * y - ry * x, rx * x + ry * y);
  if (a < 0.0) a += kTwoPi;
  return a;
}

// One triangle of the fan around a vertex: it covers the angles [lo, hi] there.
struct FanTriangle {
  int f;
  double lo, hi;
};

// A maximal run of consecutive fan triangles with one label.
struct FanRun {
  int tile;
  int begin, end;  // [begin, end) indices into the fan, end may exceed the fan size (wrap)
  double lo, hi;   // angular span
};

// Shared boundary length with each neighbouring tile, accumulated in a small vector.
class SharedLengths {
 public:
  void add(int tile, double length_m) {
    for (auto& e : entries_)
      if (e.first == tile) {
        e.second += length_m;
        return;
      }
    entries_.push_back({tile, length_m});
  }
  // The neighbour with the longest shared boundary among those allowed, ties to the
  // smallest id; -1 when none.
  template <class Allowed>
  int longest(Allowed allowed) const {
    int best = -1;
    double best_len = -1.0;
    for (const auto& e : entries_) {
      if (!allowed(e.first)) continue;
      if (e.second > best_len || (e.second == best_len && e.first < best)) {
        best = e.first;
        best_len = e.second;
      }
    }
    return best;
  }
  void clear() { entries_.clear(); }
  bool empty() const { return entries_.empty(); }

 private:
  std::vector<std::pair<int, double>> entries_;
};

class Repairer {
 public:
  Repairer(BackgroundMesh& mesh, const TriangleGeometry& geom, Tiling& tiling,
           const RepairParams& params)
      : mesh_(mesh), tags_(mesh), geom_(geom), tiling_(tiling), label_(tiling.label), params_(params) {
    const int num_vertices = static_cast<int>(mesh.points.size());
    const int num_faces = static_cast<int>(mesh.triangles.size());
    vertex_face_.assign(num_vertices, -1);
    for (int f = num_faces - 1; f >= 0; --f)
      for (int v : mesh.triangles[f]) vertex_face_[v] = f;
    next_on_boundary_.assign(num_vertices, -1);
    for (const BoundaryChain& chain : mesh.chains)
      for (std::size_t k = 0; k < chain.vertices.size(); ++k)
        next_on_boundary_[chain.vertices[k]] = chain.vertices[(k + 1) % chain.vertices.size()];
    turning_deg_ = vertex_turning_angles_deg(mesh);
    face_stamp_.assign(num_faces, 0);
    vertex_stamp_.assign(num_vertices, 0);
    cycle_stamp_.assign(num_vertices, 0);
    changed_.assign(tiling.num_tiles(), 0);
    reshaped_.assign(tiling.num_tiles(), 0);
    tile_size_.assign(tiling.num_tiles(), 0);
    for (int t : label_) ++tile_size_[t];
    visited_.assign(3 * static_cast<std::size_t>(num_faces), 0);
  }

  RepairStats run(MetaGraph* graph_out) {
    MetaGraph graph;
    bool clean = false;  // the last round found nothing to fix: `graph` is current
    // The tiles' boundaries and the tiles round every vertex, of the labels as they are:
    // the labels change only with a fix, after which the round ends, so they are those
    // of the labels each fix below reads. The meta-graph is built once, at the end: the
    // fixes need only each tile's number of meta-vertices.
    TileBoundaries b;
    std::vector<int> sectors;
    for (stats_.rounds = 0; stats_.rounds < params_.max_rounds; ++stats_.rounds) {
      touched_.assign(tiling_.num_tiles(), 0);
      // The first round, or one after a fix that left a tile in pieces, finds the
      // fragments and, at once on another thread, the boundaries and sectors from all
      // the labels. The others update the boundaries and sectors round the tiles the fix
      // changed: the tiles it did not change are as connected as they were.
      FragmentMoves fragments;
      if (stats_.rounds == 0 || !update(b, sectors)) {
        run_in_parallel([&] { fragments = find_fragments(); },
                        [&] {
                          b = walk_tile_boundaries(mesh_, label_, tiling_.num_tiles());
                          sectors = count_vertex_sectors(mesh_, label_);
                        });
      } else {
        ++stats_.rounds_updated;
        if (params_.verify_updates) verify(b, sectors);
      }
      forget_fixes();
      if (apply_fragments(fragments) > 0) continue;
      if (fix_holes(b) > 0) continue;
      if (fix_pinches(b) > 0) continue;
      // Both fixes below read the sectors; each changes nothing (labels or corner tags)
      // unless it fixes something (and the round ends).
      const std::vector<int> meta_vertices = count_tile_meta_vertices(mesh_, sectors, b);
      if (params_.verify_updates) verify_counts(b, sectors, meta_vertices);
      if (fix_small_tiles(b, meta_vertices, sectors) > 0) continue;
      if (fix_reflex_corners(sectors) > 0) continue;
      clean = true;
      graph = build_meta_graph(mesh_, tiling_, sectors, b);
      break;
    }
    std::optional<Point2> where;
    std::string problem;
    if (compact() || !clean) {  // labels renumbered, or the rounds gave up
      graph = build_meta_graph(mesh_, tiling_, params_.graph);
      problem = check_tiling(mesh_, tiling_, graph, &where);
    } else {
      problem = check_tiling(mesh_, tiling_, graph, b, &where);
    }
    if (graph_out) *graph_out = std::move(graph);
    if (!problem.empty())
      throw TilingError("cannot restore the tiling invariants after " + std::to_string(stats_.rounds) +
                            " rounds of repair: " + problem,
                        where);
    return stats_;
  }

 private:
  double edge_length_m(int h) const {
    const Point2 &a = mesh_.points[halfedge_from(mesh_, h)], &b = mesh_.points[halfedge_to(mesh_, h)];
    return std::hypot(b.x - a.x, b.y - a.y);
  }

  void relabel(int f, int tile) {
    const int old = label_[f];
    changed_[old] = 1;
    changed_[tile] = 1;
    if (old == tile) return;
    label_[f] = tile;
    --tile_size_[old];
    ++tile_size_[tile];
    relabelled_.push_back(f);
    for (int t : {old, tile})
      if (!reshaped_[t]) {
        reshaped_[t] = 1;
        reshaped_tiles_.push_back(t);
      }
  }

  int new_tile() {
    tiling_.generator.push_back(-1);
    changed_.push_back(1);
    touched_.push_back(1);
    reshaped_.push_back(0);
    tile_size_.push_back(0);
    return tiling_.num_tiles() - 1;
  }

  // --- The rounds' structures, updated round the tiles a fix changed (see run) ---

  void forget_fixes() {
    for (int t : reshaped_tiles_) reshaped_[t] = 0;
    reshaped_tiles_.clear();
    relabelled_.clear();
  }

  // Brings the boundaries and sectors of the labels before the last fix up to those of
  // the labels now. False (nothing changed) when a tile the fix changed is in pieces:
  // the fragments must then be found, from all the labels.
  bool update(TileBoundaries& b, std::vector<int>& sectors) {
    const int num_tiles = tiling_.num_tiles();
    // A triangle of each changed tile that still has any: the tile was connected, so
    // one of its triangles is, or borders, a relabelled one.
    std::vector<int>& start = start_of_tile_;
    start.assign(num_tiles, -1);
    for (int f : relabelled_) {
      if (start[label_[f]] < 0) start[label_[f]] = f;
      for (int g : mesh_.neighbours[f])
        if (g >= 0 && reshaped_[label_[g]] && start[label_[g]] < 0) start[label_[g]] = g;
    }
    // Each changed tile's cycles, walked from its triangles in the order of their ids,
    // as the walk over all the labels meets them.
    TileBoundaries walked;
    walked.tile_outer_cycle.assign(num_tiles, -1);
    walked.tile_num_cycles.assign(num_tiles, 0);
    walked.cycle_begin.push_back(0);
    auto in_pieces = [&] {
      for (int h : walked.halfedges) visited_[h] = 0;
      return false;
    };
    for (int t : reshaped_tiles_) {
      if (tile_size_[t] == 0) continue;
      if (start[t] < 0) return in_pieces();
      tile_faces_ = collect(start[t], t);
      if (static_cast<int>(tile_faces_.size()) != tile_size_[t]) return in_pieces();
      std::sort(tile_faces_.begin(), tile_faces_.end());
      for (int f : tile_faces_)
        for (int i = 0; i < 3; ++i) {
          const int h = 3 * f + i;
          if (visited_[h] || !is_tile_boundary(mesh_, label_, h)) continue;
          const CycleWalk w = walk_boundary_cycle(mesh_, label_, h, visited_, cycle_stamp_,
                                                  ++cycle_round_, walked.halfedges);
          close_cycle(walked, t, w);
        }
    }
    for (int h : walked.halfedges) visited_[h] = 0;

    // The cycles of the unchanged tiles and the new ones, by their first half-edges.
    std::vector<std::pair<int, int>> cycles;  // (first half-edge, old cycle or -1 - new cycle)
    cycles.reserve(b.num_cycles() + walked.num_cycles());
    for (int c = 0; c < b.num_cycles(); ++c)
      if (!reshaped_[b.cycle_tile[c]]) cycles.push_back({b.halfedges[b.cycle_begin[c]], c});
    for (int c = 0; c < walked.num_cycles(); ++c)
      cycles.push_back({walked.halfedges[walked.cycle_begin[c]], -1 - c});
    std::sort(cycles.begin(), cycles.end());
    TileBoundaries merged;
    merged.halfedges.reserve(b.halfedges.size() + walked.halfedges.size());
    merged.cycle_begin.reserve(cycles.size() + 1);
    merged.cycle_begin.push_back(0);
    merged.tile_outer_cycle.assign(num_tiles, -1);
    merged.tile_num_cycles.assign(num_tiles, 0);
    for (const auto& [first, id] : cycles) {
      const TileBoundaries& from = id >= 0 ? b : walked;
      const int c = id >= 0 ? id : -1 - id;
      merged.halfedges.insert(merged.halfedges.end(), from.halfedges.begin() + from.cycle_begin[c],
                              from.halfedges.begin() + from.cycle_begin[c + 1]);
      close_cycle(merged, from.cycle_tile[c], {from.cycle_area_m2[c], from.cycle_pinch[c]});
    }
    b = std::move(merged);

    // The sectors round the relabelled triangles' vertices.
    sectors.resize(mesh_.points.size());
    const int mark = ++vertex_round_;
    for (int f : relabelled_)
      for (int v : mesh_.triangles[f])
        if (vertex_stamp_[v] != mark) {
          vertex_stamp_[v] = mark;
          sectors[v] = sectors_at(v);
        }
    return true;
  }

  // The triangles round v in increasing id order, as a list of every vertex's triangles
  // gives them: turning round v across its edges one way, then, when a domain boundary
  // stops the turn, the other way from the first.
  void faces_around(int v, std::vector<int>& out) const {
    out.clear();
    const int first = vertex_face_[v];
    auto next = [&](int f, int side) {  // side 1 or 2: the neighbour across an edge at v
      const auto& t = mesh_.triangles[f];
      const int i = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      return mesh_.neighbours[f][(i + side) % 3];
    };
    int f = first;
    do {
      out.push_back(f);
      f = next(f, 2);
    } while (f >= 0 && f != first);
    if (f < 0)
      for (f = next(first, 1); f >= 0; f = next(f, 1)) out.push_back(f);
    std::sort(out.begin(), out.end());
  }

  // count_vertex_sectors at one vertex.
  int sectors_at(int v) const {
    int changes = 0;
    faces_around(v, fan_scratch_);
    for (const int f : fan_scratch_) {
      const auto& t = mesh_.triangles[f];
      for (int i = 0; i < 3; ++i) {
        if (t[i] == v) continue;  // the edge opposite v does not end at v
        const int g = mesh_.neighbours[f][i];
        if (g > f && label_[g] != label_[f]) ++changes;
      }
    }
    // The boundary chains hold every vertex of a domain boundary edge.
    return next_on_boundary_[v] >= 0 ? changes + 1 : std::max(changes, 1);
  }

  // RepairParams::verify_updates: the meta-vertices counted per tile against the graph's.
  void verify_counts(const TileBoundaries& b, const std::vector<int>& sectors,
                     const std::vector<int>& meta_vertices) {
    const MetaGraph graph = build_meta_graph(mesh_, tiling_, sectors, b);
    for (int t = 0; t < tiling_.num_tiles(); ++t)
      if (meta_vertices[t] != static_cast<int>(graph.tiles[t].vertices.size()))
        throw Error(ErrorClass::internal, "tiling",
                    "repair round " + std::to_string(stats_.rounds) + ": tile " +
                        std::to_string(t) + " has " + std::to_string(meta_vertices[t]) +
                        " meta-vertices by count, " +
                        std::to_string(graph.tiles[t].vertices.size()) + " in the graph");
  }

  // RepairParams::verify_updates: the updated structures against those of all the labels.
  void verify(const TileBoundaries& b, const std::vector<int>& sectors) {
    const TileBoundaries all = walk_tile_boundaries(mesh_, label_, tiling_.num_tiles());
    const char* what = nullptr;
    if (!find_fragments().moves.empty())
      what = "a fragment";
    else if (sectors != count_vertex_sectors(mesh_, label_))
      what = "the vertex sectors";
    else if (b.halfedges != all.halfedges || b.cycle_begin != all.cycle_begin)
      what = "the cycles";
    else if (b.cycle_tile != all.cycle_tile || b.cycle_area_m2 != all.cycle_area_m2 ||
             b.cycle_pinch != all.cycle_pinch)
      what = "the cycles' tiles, areas or pinches";
    else if (b.tile_outer_cycle != all.tile_outer_cycle || b.tile_num_cycles != all.tile_num_cycles)
      what = "the tiles' cycles";
    if (what)
      throw Error(ErrorClass::internal, "tiling",
                  std::string("repair round ") + std::to_string(stats_.rounds) + ": " + what +
                      " differ from those of all the labels");
  }

  // The triangles of `tile` connected to `start` (which must carry that label).
  const std::vector<int>& collect(int start, int tile) {
    ++face_round_;
    members_.assign(1, start);
    face_stamp_[start] = face_round_;
    for (std::size_t k = 0; k < members_.size(); ++k)
      for (int g : mesh_.neighbours[members_[k]])
        if (g >= 0 && label_[g] == tile && face_stamp_[g] != face_round_) {
          face_stamp_[g] = face_round_;
          members_.push_back(g);
        }
    return members_;
  }

  // The fan around v sorted counter-clockwise; on the domain boundary it starts at the
  // boundary edge leaving v (the domain is on its left) and ends at the one entering v.
  std::vector<FanTriangle> fan(int v) const {
    std::vector<FanTriangle> out;
    const Point2& pv = mesh_.points[v];
    int ref = next_on_boundary_[v];
    std::vector<int> faces;
    faces_around(v, faces);
    for (const int f : faces) {
      const auto& t = mesh_.triangles[f];
      const int i = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      if (ref < 0) ref = t[(i + 1) % 3];
      const Point2& r = mesh_.points[ref];
      const Point2 &a = mesh_.points[t[(i + 1) % 3]], &b = mesh_.points[t[(i + 2) % 3]];
      const double rx = r.x - pv.x, ry = r.y - pv.y;
      double lo = angle_from(rx, ry, a.x - pv.x, a.y - pv.y);
      double hi = angle_from(rx, ry, b.x - pv.x, b.y - pv.y);
      if (hi < lo) hi += kTwoPi;
      out.push_back({f, lo, hi});
    }
    std::sort(out.begin(), out.end(), [](const FanTriangle& x, const FanTriangle& y) {
      return x.lo != y.lo ? x.lo < y.lo : x.f < y.f;
    });
    return out;
  }

  // Runs of equal labels in the fan; around an interior vertex the fan is circular and a
  // run may wrap past the end.
  std::vector<FanRun> runs(const std::vector<FanTriangle>& fan, bool circular) const {
    std::vector<FanRun> out;
    const int n = static_cast<int>(fan.size());
    int start = 0;
    if (circular) {
      while (start < n && label_[fan[start].f] == label_[fan[(start + n - 1) % n].f]) ++start;
      if (start == n) return {{label_[fan[0].f], 0, n, fan[0].lo, fan[0].lo + kTwoPi}};
    }
    for (int k = start; k < start + n;) {
      const int tile = label_[fan[k % n].f];
      int e = k + 1;
      while (e < start + n && label_[fan[e % n].f] == tile) ++e;
      double lo = fan[k % n].lo, hi = fan[(e - 1) % n].hi;
      if (hi < lo) hi += kTwoPi;
      out.push_back({tile, k, e, lo, hi});
      k = e;
    }
    return out;
  }

  // Disconnected parts of a tile (other than the one holding its generator, or else the
  // largest) join the neighbouring tile they share the longest boundary with: found from
  // the labels as they are (read only, so that other readers can run meanwhile), then
  // moved by apply_fragments.
  struct FragmentMoves {
    std::vector<int> order, comp_begin;  // the components' triangles, one after the other
    std::vector<std::pair<int, int>> moves;  // (component, target tile or -1)
  };
  FragmentMoves find_fragments() {
    FragmentMoves out;
    const int num_faces = static_cast<int>(label_.size());
    const int num_tiles = tiling_.num_tiles();
    std::vector<int> comp(num_faces, -1), comp_tile;
    std::vector<int>& comp_begin = out.comp_begin;
    std::vector<int>& order = out.order;
    order.reserve(num_faces);
    for (int f = 0; f < num_faces; ++f) {
      if (comp[f] >= 0) continue;
      const int c = static_cast<int>(comp_tile.size());
      comp_tile.push_back(label_[f]);
      comp_begin.push_back(static_cast<int>(order.size()));
      for (int g : collect(f, label_[f])) {
        comp[g] = c;
        order.push_back(g);
      }
    }
    const int num_comps = static_cast<int>(comp_tile.size());
    comp_begin.push_back(num_faces);
    if (num_comps == num_tiles) return out;
    auto size_of = [&](int c) { return comp_begin[c + 1] - comp_begin[c]; };
    std::vector<int> keep(num_tiles, -1);
    for (int c = 0; c < num_comps; ++c) {
      const int t = comp_tile[c];
      const int g = tiling_.generator[t];
      if (g >= 0 && g < num_faces && label_[g] == t) {
        keep[t] = comp[g];
      } else if (keep[t] < 0 || size_of(c) > size_of(keep[t])) {
        keep[t] = c;
      }
    }
    SharedLengths shared;
    for (int c = 0; c < num_comps; ++c) {
      if (keep[comp_tile[c]] == c) continue;
      shared.clear();
      for (int k = comp_begin[c]; k < comp_begin[c + 1]; ++k) {
        const int f = order[k];
        for (int i = 0; i < 3; ++i) {
          const int g = mesh_.neighbours[f][i];
          if (g >= 0 && label_[g] != comp_tile[c]) shared.add(label_[g], edge_length_m(3 * f + i));
        }
      }
      out.moves.push_back({c, shared.longest([](int) { return true; })});
    }
    return out;
  }
  int apply_fragments(const FragmentMoves& found) {
    for (const auto& [c, target] : found.moves) {
      const int tile = target >= 0 ? target : new_tile();  // alone in its mesh component
      for (int k = found.comp_begin[c]; k < found.comp_begin[c + 1]; ++k)
        relabel(found.order[k], tile);
      ++stats_.fragments_merged;
    }
    return static_cast<int>(found.moves.size());
  }

  // Tiles with more than one boundary cycle enclose something: other tiles (merged into
  // the tile when they weigh at most one tile) or an island (the ring is cut open).
  int fix_holes(const TileBoundaries& b) {
    int fixes = 0;
    std::vector<int> inner(tiling_.num_tiles(), -1);
    for (int c = 0; c < b.num_cycles(); ++c) {
      const int t = b.cycle_tile[c];
      if (c != b.tile_outer_cycle[t] && inner[t] < 0) inner[t] = c;
    }
    for (int t = 0; t < tiling_.num_tiles(); ++t) {
      if (inner[t] < 0 || touched_[t]) continue;
      const int c = inner[t];
      // What lies inside: a search from across the hole's boundary that never enters t.
      ++face_round_;
      enclosed_.clear();
      for (int k = b.cycle_begin[c]; k < b.cycle_begin[c + 1]; ++k) {
        const int g = halfedge_across(mesh_, b.halfedges[k]);
        if (g >= 0 && face_stamp_[g] != face_round_) {
          face_stamp_[g] = face_round_;
          enclosed_.push_back(g);
        }
      }
      double mass = 0.0;
      bool conflict = false;
      for (std::size_t k = 0; k < enclosed_.size(); ++k) {
        const int f = enclosed_[k];
        mass += geom_.mass(f);
        conflict = conflict || touched_[label_[f]];
        for (int g : mesh_.neighbours[f])
          if (g >= 0 && label_[g] != t && face_stamp_[g] != face_round_) {
            face_stamp_[g] = face_round_;
            enclosed_.push_back(g);
          }
      }
      if (conflict) continue;
      if (!enclosed_.empty() && mass <= 1.0) {
        std::vector<int> tiles;
        for (int f : enclosed_) tiles.push_back(label_[f]);
        std::sort(tiles.begin(), tiles.end());
        stats_.enclosed_merged += static_cast<int>(std::unique(tiles.begin(), tiles.end()) - tiles.begin());
        for (int f : enclosed_) {
          touched_[label_[f]] = 1;
          relabel(f, t);
        }
        touched_[t] = 1;
        ++fixes;
      } else if (cut_ring(t, c, b)) {
        ++fixes;
      }
    }
    return fixes;
  }

  // Opens the ring `tile` around its hole `cycle`: the shortest edge path through the
  // tile from the hole to a vertex it shares with a neighbouring tile; the tile's
  // triangles around that path go to the neighbour. Without such a neighbour (the tile
  // covers its whole mesh component), the tile is split in two across the hole.
  bool cut_ring(int tile, int cycle, const TileBoundaries& b) {
    const int outer = b.tile_outer_cycle[tile];
    ++vertex_round_;
    const int outer_mark = vertex_round_;
    for (int k = b.cycle_begin[outer]; k < b.cycle_begin[outer + 1]; ++k)
      vertex_stamp_[halfedge_from(mesh_, b.halfedges[k])] = outer_mark;
    std::vector<int> faces_x, faces_v;
    auto other_tile_at = [&](int v) {
      faces_around(v, faces_v);
      for (const int f : faces_v)
        if (label_[f] != tile) return label_[f];
      return -1;
    };
    // Breadth-first from the hole's vertices; a vertex is a target when it lies on the
    // outer cycle (read before its stamp is overwritten) and touches another tile.
    ++vertex_round_;
    const int seen = vertex_round_;
    // Sized at the first ring cut: most tilings have none.
    if (vertex_parent_.empty()) vertex_parent_.assign(mesh_.points.size(), -1);
    std::vector<int> queue;
    int found = -1;
    double hole_y = 0.0;
    const int hole_begin = b.cycle_begin[cycle], hole_end = b.cycle_begin[cycle + 1];
    for (int k = hole_begin; k < hole_end; ++k) {
      const int v = halfedge_from(mesh_, b.halfedges[k]);
      hole_y += mesh_.points[v].y;
      if (vertex_stamp_[v] == seen) continue;
      const bool was_outer = vertex_stamp_[v] == outer_mark;
      vertex_stamp_[v] = seen;
      vertex_parent_[v] = -1;
      if (found < 0 && was_outer && other_tile_at(v) >= 0) found = v;
      queue.push_back(v);
    }
    hole_y /= hole_end - hole_begin;
    for (std::size_t q = 0; q < queue.size() && found < 0; ++q) {
      const int x = queue[q];
      faces_around(x, faces_x);
      for (std::size_t k = 0; k < faces_x.size() && found < 0; ++k) {
        const int f = faces_x[k];
        if (label_[f] != tile) continue;
        for (int y : mesh_.triangles[f]) {
          if (vertex_stamp_[y] == seen) continue;
          const bool was_outer = vertex_stamp_[y] == outer_mark;
          vertex_stamp_[y] = seen;
          vertex_parent_[y] = x;
          if (was_outer && other_tile_at(y) >= 0) {
            found = y;
            break;
          }
          queue.push_back(y);
        }
      }
    }
    if (found >= 0) {
      const int target = other_tile_at(found);
      if (touched_[target]) return false;
      std::vector<int> band;
      for (int v = found; v >= 0; v = vertex_parent_[v]) {
        faces_around(v, faces_v);
        for (const int f : faces_v)
          if (label_[f] == tile) band.push_back(f);
      }
      for (int f : band) relabel(f, target);
      touched_[tile] = touched_[target] = 1;
      ++stats_.rings_cut;
      return true;
    }
    // Split across the hole: the tile's triangles above the hole's centre form a new
    // tile; each half is then open (stray pieces are merged as fragments).
    const std::vector<int> members = collect(b.halfedges[b.cycle_begin[outer]] / 3, tile);
    const int part = new_tile();
    for (int f : members)
      if (geom_.cy[f] > hole_y) relabel(f, part);
    touched_[tile] = 1;
    ++stats_.tiles_split;
    return true;
  }

  // A tile touching itself at a vertex: its smallest sector there joins the next tile
  // around the vertex.
  int fix_pinches(const TileBoundaries& b) {
    int fixes = 0;
    for (int c = 0; c < b.num_cycles(); ++c) {
      const int v = b.cycle_pinch[c];
      const int tile = b.cycle_tile[c];
      if (v < 0 || touched_[tile]) continue;
      const bool circular = next_on_boundary_[v] < 0;
      const std::vector<FanTriangle> fan_v = fan(v);
      const std::vector<FanRun> r = runs(fan_v, circular);
      const int n = static_cast<int>(r.size());
      int smallest = -1;
      for (int k = 0; k < n; ++k)
        if (r[k].tile == tile &&
            (smallest < 0 || r[k].end - r[k].begin < r[smallest].end - r[smallest].begin))
          smallest = k;
      if (smallest < 0) continue;
      int next = -1;
      if (circular) next = (smallest + 1) % n;
      else next = smallest + 1 < n ? smallest + 1 : smallest - 1;
      if (next < 0 || r[next].tile == tile || touched_[r[next].tile]) continue;
      const int target = r[next].tile;
      const int m = static_cast<int>(fan_v.size());
      for (int k = r[smallest].begin; k < r[smallest].end; ++k) relabel(fan_v[k % m].f, target);
      touched_[tile] = touched_[target] = 1;
      ++stats_.pinches_split;
      ++fixes;
    }
    return fixes;
  }

  bool is_reflex_corner(int v) const {
    return next_on_boundary_[v] >= 0 && turning_deg_[v] < 0.0;
  }

  // Tiles with fewer than 3 meta-vertices (count_tile_meta_vertices) join the neighbour
  // they share the longest boundary with, unless that would leave a reflex corner in a
  // single tile.
  int fix_small_tiles(const TileBoundaries& b, const std::vector<int>& meta_vertices,
                      const std::vector<int>& sectors) {
    int fixes = 0;
    SharedLengths shared;
    std::vector<int> forbidden;
    for (int t = 0; t < tiling_.num_tiles(); ++t) {
      if (touched_[t] || meta_vertices[t] >= 3) continue;  // new tiles are touched
      const int c = b.tile_outer_cycle[t];
      if (c < 0) continue;
      shared.clear();
      forbidden.clear();
      for (int k = b.cycle_begin[c]; k < b.cycle_begin[c + 1]; ++k) {
        const int h = b.halfedges[k];
        const int g = halfedge_across(mesh_, h);
        if (g >= 0) shared.add(label_[g], edge_length_m(h));
        const int v = halfedge_from(mesh_, h);
        if (is_reflex_corner(v) && sectors[v] <= 2) {
          faces_around(v, fan_scratch_);
          for (const int f : fan_scratch_)
            if (label_[f] != t) forbidden.push_back(label_[f]);
        }
      }
      if (shared.empty()) {
        // An island split before that is one small tile again (its parts were too small
        // to keep three meta-vertices each and merged back) takes closer corners.
        const std::vector<int> members = collect(b.halfedges[b.cycle_begin[c]] / 3, t);
        const int island = *std::min_element(members.begin(), members.end());
        const bool split_before =
            std::find(islands_split_.begin(), islands_split_.end(), island) != islands_split_.end();
        if (tag_island_corners(t, b, split_before ? 12.0 : 8.0)) {
          ++fixes;
        } else if (split_isolated(t, b, members)) {
          islands_split_.push_back(island);
          ++fixes;
        }
        continue;
      }
      auto allowed = [&](int x) {
        return std::find(forbidden.begin(), forbidden.end(), x) == forbidden.end();
      };
      int target = shared.longest(allowed);
      if (target < 0) target = shared.longest([](int) { return true; });
      if (touched_[target]) continue;
      for (int f : collect(b.halfedges[b.cycle_begin[c]] / 3, t)) relabel(f, target);
      touched_[t] = touched_[target] = 1;
      ++stats_.small_tiles_merged;
      ++fixes;
    }
    return fixes;
  }

  // A tile alone in its mesh component with fewer than 3 meta-vertices (an island about
  // one tile large, with fewer than 3 corners): its most convex boundary vertices, at
  // least perimeter / spacing from each other and from its corners, become corners
  // until it has four (at least three), so that it subdivides into four (three) quads
  // around its centroid, about the size asked for. Only vertices turning left by at
  // least 10 degrees qualify (the quads' angles there are 180 minus the turn). Spacing 8
  // first; 12 for an island whose split (split_isolated) came back as one tile: a 14 by
  // 5 km sliver of water with quads 8 km wide, whose turning vertices cluster at its
  // two ends, was split, merged back, split again for 200 rounds.
  bool tag_island_corners(int tile, const TileBoundaries& b, double spacing) {
    const int c = b.tile_outer_cycle[tile];
    const int begin = b.cycle_begin[c], n = b.cycle_begin[c + 1] - begin;
    struct Candidate {
      double turn;
      double arc;
      int vertex;
    };
    std::vector<Candidate> cands, chosen;  // chosen starts with the corners it has
    double arc = 0.0;
    for (int k = 0; k < n; ++k) {
      const int h = b.halfedges[begin + k];
      const int v = halfedge_from(mesh_, h);
      if (halfedge_across(mesh_, h) >= 0) return false;  // not alone after all
      const int chain = mesh_.boundary_chain_of_vertex[v];
      if (chain >= 0) {
        const BoundaryChain& ch = tags_.chains[chain];
        const std::size_t at = std::find(ch.vertices.begin(), ch.vertices.end(), v) - ch.vertices.begin();
        const double turn = ch.turning_angle_deg[at];
        if (ch.is_corner[at])
          chosen.push_back({turn, arc, -1});
        else if (turn >= 10.0)
          cands.push_back({turn, arc, v});
      }
      arc += edge_length_m(h);
    }
    const double perimeter = arc;
    std::stable_sort(cands.begin(), cands.end(),
                     [](const Candidate& x, const Candidate& y) { return x.turn > y.turn; });
    for (const Candidate& x : cands) {
      bool apart = true;
      for (const Candidate& y : chosen) {
        const double d = std::abs(x.arc - y.arc);
        apart = apart && std::min(d, perimeter - d) >= perimeter / spacing;
      }
      if (apart) chosen.push_back(x);
      if (chosen.size() == 4) break;
    }
    if (chosen.size() < 3) return false;
    for (const Candidate& x : chosen)
      if (x.vertex >= 0) promote_corner(x.vertex, x.turn);
    touched_[tile] = 1;
    ++stats_.corners_added;
    return true;
  }

  // A tile alone in its mesh component with fewer than 3 meta-vertices whose boundary
  // has not three such corners: three tiles grown from three points evenly spaced along its
  // boundary, which meet at one interior meta-vertex.
  bool split_isolated(int tile, const TileBoundaries& b, const std::vector<int>& members) {
    const int c = b.tile_outer_cycle[tile];
    const int begin = b.cycle_begin[c], n = b.cycle_begin[c + 1] - begin;
    if (n < 3) return false;
    if (members.size() < 3) return false;
    int seeds[3];
    for (int s = 0; s < 3; ++s) seeds[s] = b.halfedges[begin + s * n / 3] / 3;
    if (seeds[0] == seeds[1] || seeds[1] == seeds[2] || seeds[0] == seeds[2]) return false;
    const int parts[3] = {tile, new_tile(), new_tile()};
    // Grow the three parts by distance to their seeds (a small Voronoi flood).
    using Entry = std::pair<double, std::pair<int, int>>;  // distance, (triangle, part)
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    ++face_round_;
    const int fresh = face_round_;
    for (int f : members) face_stamp_[f] = fresh;  // unassigned members
    for (int s = 0; s < 3; ++s) queue.push({0.0, {seeds[s], s}});
    while (!queue.empty()) {
      const auto [d, item] = queue.top();
      queue.pop();
      const int f = item.first, s = item.second;
      if (face_stamp_[f] != fresh) continue;
      face_stamp_[f] = fresh - 1;
      relabel(f, parts[s]);
      for (int g : mesh_.neighbours[f])
        if (g >= 0 && face_stamp_[g] == fresh) {
          const double dx = geom_.cx[g] - geom_.cx[seeds[s]], dy = geom_.cy[g] - geom_.cy[seeds[s]];
          queue.push({std::hypot(dx, dy), {g, s}});
        }
    }
    ++face_round_;
    touched_[tile] = 1;
    ++stats_.tiles_split;
    return true;
  }

  // A reflex corner in fewer tiles than it needs: the tile with the widest sector there
  // is split by rays from the corner into equal angles.
  int fix_reflex_corners(const std::vector<int>& sectors) {
    int fixes = 0;
    for (const BoundaryChain& chain : mesh_.chains) {
      for (std::size_t k = 0; k < chain.vertices.size(); ++k) {
        const int v = chain.vertices[k];
        if (!is_reflex_corner(v)) continue;
        const int attempts = split_attempts(v);
        const bool sharp = turning_deg_[v] < -params_.sharp_reflex_deg && attempts < 2;
        const int need = sharp ? 3 : 2;
        if (sectors[v] >= need) continue;
        const std::vector<FanTriangle> fan_v = fan(v);
        const std::vector<FanRun> r = runs(fan_v, false);
        int widest = 0;
        for (int q = 1; q < static_cast<int>(r.size()); ++q)
          if (r[q].hi - r[q].lo > r[widest].hi - r[widest].lo) widest = q;
        const int tile = r[widest].tile;
        if (touched_[tile]) continue;
        const int num_parts = need - sectors[v] + 1;
        if (attempts >= params_.max_corner_splits) {
          demote_corner(v);
          ++fixes;
          continue;
        }
        // A corner met again (its neighbour moved away): give it a tile of its own.
        split_from_corner(fan_v, r[widest], num_parts, attempts < 2);
        ++split_attempts_[v];
        touched_[tile] = 1;
        ++stats_.tiles_split;
        ++fixes;
      }
    }
    return fixes;
  }

  // Splits the tile of `run` (a run of the fan around a boundary corner) into num_parts
  // connected tiles: the run's triangles are divided into num_parts equal angular ranges,
  // and every other triangle of the tile joins the range whose triangles are nearest
  // (Dijkstra over centroids inside the tile), so that each part is connected.
  void split_from_corner(const std::vector<FanTriangle>& fan_v, const FanRun& run, int num_parts,
                         bool allow_merge) {
    const int tile = run.tile;
    const int n = static_cast<int>(fan_v.size());
    const std::vector<int> members = collect(fan_v[run.begin % n].f, tile);
    std::vector<int> part_tile(num_parts, tile);
    for (int q = 1; q < num_parts; ++q) part_tile[q] = new_tile();
    const double width = (run.hi - run.lo) / num_parts;
    using Item = std::pair<double, int>;  // (distance, triangle)
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    // Per triangle reached: its distance and its part (a tile's triangles, not the mesh's).
    std::unordered_map<int, std::pair<double, int>> reached;
    for (int k = run.begin; k < run.end; ++k) {
      const FanTriangle& ft = fan_v[k % n];
      double mid = 0.5 * (ft.lo + ft.hi);
      if (mid < run.lo) mid += kTwoPi;
      const int q = std::clamp(static_cast<int>((mid - run.lo) / width), 0, num_parts - 1);
      reached[ft.f] = {0.0, q};
      queue.push({0.0, ft.f});
    }
    while (!queue.empty()) {
      const auto [d, f] = queue.top();
      queue.pop();
      const auto [best, part] = reached.at(f);
      if (d > best) continue;
      for (int g : mesh_.neighbours[f]) {
        if (g < 0 || label_[g] != tile) continue;
        const double nd = d + std::hypot(geom_.cx[g] - geom_.cx[f], geom_.cy[g] - geom_.cy[f]);
        const auto it = reached.find(g);
        if (it == reached.end() || nd < it->second.first) {
          reached[g] = {nd, part};
          queue.push({nd, g});
        }
      }
    }
    for (int f : members) {
      const auto it = reached.find(f);
      if (it != reached.end() && it->second.second > 0) relabel(f, part_tile[it->second.second]);
    }
    if (num_parts != 2 || !allow_merge) return;
    // Two parts: rather than add a tile, the lighter part joins the neighbour it shares
    // most boundary with when it is small (the tiles next to the corner then meet there);
    // the relaxation keeps the number of tiles, so new tiles would accumulate step after
    // step.
    double mass[2] = {0.0, 0.0};
    for (int f : members) mass[label_[f] == tile ? 0 : 1] += geom_.mass(f);
    const int light = mass[1] <= mass[0] ? 1 : 0;
    if (mass[light] > params_.max_merged_part_mass) return;
    SharedLengths shared;
    for (int f : members) {
      if (label_[f] != part_tile[light]) continue;
      for (int i = 0; i < 3; ++i) {
        const int g = mesh_.neighbours[f][i];
        if (g >= 0 && label_[g] != part_tile[0] && label_[g] != part_tile[1])
          shared.add(label_[g], edge_length_m(3 * f + i));
      }
    }
    const int into = shared.longest([](int) { return true; });
    if (into < 0) return;
    for (int f : members)
      if (label_[f] == part_tile[light]) relabel(f, into);
    touched_[into] = 1;
  }

  // Tags v as a corner that turns by turn_deg (> 0: convex).
  void promote_corner(int v, double turn_deg) {
    for (BoundaryChain& chain : tags_.chains)
      for (std::size_t k = 0; k < chain.vertices.size(); ++k)
        if (chain.vertices[k] == v) {
          chain.is_corner[k] = 1;
          chain.corner_turning_deg[k] = turn_deg;
        }
    turning_deg_[v] = turn_deg;
  }

  // Clears the corner tag of v: the tiles keep undoing its splits (a narrow spike or
  // inlet). Its quads then cut across the corner, convex.
  void demote_corner(int v) {
    for (BoundaryChain& chain : tags_.chains)
      for (std::size_t k = 0; k < chain.vertices.size(); ++k)
        if (chain.vertices[k] == v) {
          chain.is_corner[k] = 0;
          chain.corner_turning_deg[k] = 0.0;
        }
    turning_deg_[v] = 0.0;
    ++stats_.corners_demoted;
  }

  // Drops empty tiles (keeping the order of the others) and relocates the generators of
  // the tiles that changed. True if there were empty tiles (labels renumbered).
  bool compact() {
    const int num_tiles = tiling_.num_tiles();
    std::vector<int> count(num_tiles, 0);
    for (int t : label_) ++count[t];
    const bool renumber = std::find(count.begin(), count.end(), 0) != count.end();
    std::vector<int> id(num_tiles, -1);
    std::vector<int> generator;
    for (int t = 0; t < num_tiles; ++t) {
      if (count[t] == 0) continue;
      id[t] = static_cast<int>(generator.size());
      generator.push_back(changed_[t] ? -1 : tiling_.generator[t]);
    }
    if (renumber)
      for (int& t : label_) t = id[t];
    tiling_.generator.swap(generator);
    fix_generators(geom_, tiling_);
    return renumber;
  }

  const BackgroundMesh& mesh_;
  BackgroundMesh& tags_;  // the same mesh: corner tags may be cleared (demote_corner)
  const TriangleGeometry& geom_;
  Tiling& tiling_;
  std::vector<int>& label_;
  const RepairParams& params_;
  RepairStats stats_;
  // #V a triangle at each vertex, the first in id order: the others are found by turning
  // round it (faces_around), without a list of every vertex's triangles (the mesh's
  // triangles three times over, the largest array of the tiling's peak).
  std::vector<int> vertex_face_;
  mutable std::vector<int> fan_scratch_;          // faces_around's output where no other call nests
  std::vector<int> next_on_boundary_;             // next chain vertex, -1 inside
  std::vector<double> turning_deg_;
  std::vector<int> face_stamp_, vertex_stamp_;
  std::vector<int> vertex_parent_;  // #V scratch of the ring cuts, sized at the first
  int face_round_ = 0, vertex_round_ = 0;
  std::vector<int> members_, enclosed_;
  // Splits tried at each reflex corner (a few corners: not an array over the vertices).
  std::unordered_map<int, int> split_attempts_;
  int split_attempts(int v) const {
    const auto it = split_attempts_.find(v);
    return it == split_attempts_.end() ? 0 : it->second;
  }
  std::vector<int> islands_split_;  // islands split by split_isolated, by their first triangle
  std::vector<char> changed_, touched_;
  // Since the round's structures were found: the triangles relabelled, the tiles they
  // left or joined (reshaped_ #T), and every tile's number of triangles.
  std::vector<int> relabelled_, reshaped_tiles_, tile_size_;
  std::vector<char> reshaped_;
  std::vector<char> visited_;             // #3F scratch of update, all 0 between calls
  std::vector<int> cycle_stamp_;          // #V scratch of update
  int cycle_round_ = 0;
  std::vector<int> start_of_tile_, tile_faces_;
};

}  // namespace

RepairStats repair_tiling(BackgroundMesh& mesh, const TriangleGeometry& geom,
                          Tiling& tiling, const RepairParams& params, MetaGraph* graph) {
  if (tiling.label.size() != mesh.triangles.size())
    throw Error(ErrorClass::internal, "tiling", "repair: the labelling does not match the mesh");
  for (int t : tiling.label)
    if (t < 0 || t >= tiling.num_tiles())
      throw Error(ErrorClass::internal, "tiling", "repair: a triangle has no tile");
  Repairer repairer(mesh, geom, tiling, params);
  return repairer.run(graph);
}

}  // namespace isoquad
