// SCHISM horizontal grid (hgrid.gr3 / hgrid.ll): nodes with depth (metres, positive
// down), elements (type 4 for quads, 3 for the triangles of a split quad), then the open
// boundary segments and the land boundary segments (flag 0 on the exterior boundary, 1
// on an island) in SCHISM's layout.
#include <cstdio>
#include <vector>

#include "core/text.h"
#include "gis/crs.h"
#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

namespace {

// The quads that --schism-split writes as two triangles, decided on the mesh as meshed
// (metres), so that hgrid.gr3, hgrid.ll and hgrid.prop have the same elements.
std::vector<char> split_quads(const QuadMesh& m, bool schism_split, std::size_t& num_split) {
  std::vector<char> split(m.quads.size(), 0);
  num_split = 0;
  if (schism_split)
    for (std::size_t q = 0; q < m.quads.size(); ++q)
      num_split += split[q] = fails_schism_checks(m, static_cast<int>(q));
  return split;
}

// The boundary segments as SCHISM takes them: nodes in order and the land flag. A whole
// loop of land on the exterior boundary is written as two segments that share their
// ends, as its developers ask (a whole loop open is two already, extract_boundary:
// SCHISM stops on an open segment whose first node is its last, "Looped open bnd"); an
// island's whole loop stays one segment (flag 1), which SCHISM closes.
struct SchismSegment {
  std::vector<int> nodes;
  bool island = false;
};

std::vector<SchismSegment> schism_segments(const std::vector<const BoundarySegment*>& segments) {
  std::vector<SchismSegment> out;
  for (const BoundarySegment* s : segments) {
    const std::size_t n = s->nodes.size();
    if (!s->closed || (s->kind == BoundaryKind::land && s->island) || n < 3) {
      out.push_back({s->nodes, s->island});
      continue;
    }
    for (std::vector<int>& half : loop_halves(s->nodes))
      out.push_back({std::move(half), s->island});
  }
  return out;
}

}  // namespace

void write_prop_file(const MeshView& v, const std::string& path, const std::string& what,
                     bool schism_split) {
  const QuadMesh& m = *v.data->mesh;
  std::size_t num_split = 0;
  const std::vector<char> split = split_quads(m, schism_split, num_split);
  OutputFile f(path, what);
  std::size_t e = 0;
  for (std::size_t q = 0; q < m.quads.size(); ++q)
    for (int k = 0; k < (split[q] ? 2 : 1); ++k)
      std::fprintf(f.get(), "%zu %lld\n", ++e, static_cast<long long>(v.data->zone[q]));
  f.close();
}

std::string title_crs_note(const MeshView& v) {
  const int epsg = epsg_code(v.crs_wkt);
  const std::string crs =
      epsg > 0 ? "EPSG:" + std::to_string(epsg) : crs_proj_string(CrsInfo{v.crs_wkt, ""});
  return crs.empty() ? "" : " CRS: " + crs;
}

void write_gr3_file(const MeshView& v, const std::vector<Point2>& points, const std::string& path,
                    const std::string& what, bool schism_split) {
  const QuadMesh& m = *v.data->mesh;
  const auto& depth = v.data->depth;
  const int nq = static_cast<int>(m.quads.size());
  std::size_t num_split = 0;
  const std::vector<char> split = split_quads(m, schism_split, num_split);
  OutputFile f(path, what);
  std::FILE* raw = f.get();
  const char* xy = v.geographic ? "%zu %.10f %.10f %.6f\n" : "%zu %.6f %.6f %.6f\n";
  // The title line (which SCHISM skips) says the coordinates' CRS, so that a grid alone
  // is enough to place it.
  const std::string split_note =
      num_split ? printf_string("; %zu quads failing SCHISM's checks as triangle pairs", num_split)
                : std::string();
  std::fprintf(raw, "isoquad mesh (depth in metres, positive down%s)%s\n", split_note.c_str(),
               title_crs_note(v).c_str());
  std::fprintf(raw, "%zu %zu\n", m.quads.size() + num_split, points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    std::fprintf(raw, xy, i + 1, points[i].x, points[i].y, depth.empty() ? 0.0 : depth[i]);
  std::size_t e = 0;
  for (int q = 0; q < nq; ++q) {
    if (split[q]) {
      for (const auto& t : quad_as_triangles(m, q))
        std::fprintf(raw, "%zu 3 %d %d %d\n", ++e, t[0] + 1, t[1] + 1, t[2] + 1);
    } else {
      const auto& c = m.quads[q];
      std::fprintf(raw, "%zu 4 %d %d %d %d\n", ++e, c[0] + 1, c[1] + 1, c[2] + 1, c[3] + 1);
    }
  }
  std::vector<const BoundarySegment*> open_runs, land_runs;
  for (const auto& s : v.data->boundary.segments)
    (s.kind == BoundaryKind::open ? open_runs : land_runs).push_back(&s);
  const std::vector<SchismSegment> open = schism_segments(open_runs),
                                   land = schism_segments(land_runs);
  auto total = [](const std::vector<SchismSegment>& ss) {
    std::size_t n = 0;
    for (const auto& s : ss) n += s.nodes.size();
    return n;
  };
  std::fprintf(raw, "%zu = Number of open boundaries\n", open.size());
  std::fprintf(raw, "%zu = Total number of open boundary nodes\n", total(open));
  for (std::size_t k = 0; k < open.size(); ++k) {
    std::fprintf(raw, "%zu = Number of nodes for open boundary %zu\n", open[k].nodes.size(), k + 1);
    for (int n : open[k].nodes) std::fprintf(raw, "%d\n", n + 1);
  }
  std::fprintf(raw, "%zu = Number of land boundaries\n", land.size());
  std::fprintf(raw, "%zu = Total number of land boundary nodes\n", total(land));
  for (std::size_t k = 0; k < land.size(); ++k) {
    std::fprintf(raw, "%zu %d = Number of nodes for land boundary %zu\n", land[k].nodes.size(),
                 land[k].island ? 1 : 0, k + 1);
    for (int n : land[k].nodes) std::fprintf(raw, "%d\n", n + 1);
  }
  f.close();
}

}  // namespace isoquad
