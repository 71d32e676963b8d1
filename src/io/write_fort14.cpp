// ADCIRC grid and boundary file (fort.14). ADCIRC computes on linear triangles only, so
// each quad is cut into two (quad_as_triangles). Nodes with depth (metres,
// positive down), elements (3 nodes each), the open boundary segments (NOPE, NETA) and
// the flux boundaries (NBOU, NVEL): the outer loops' land segments first, in order
// round the domain, then the islands', as ADCIRC's manual asks; mainland segments are
// IBTYPE 20, islands 21 (no normal flow, natural: the types the manual recommends over
// 0 and 1), and a whole loop of land lists its first node again at its end. The open
// segments are hgrid.gr3's: a whole loop open (a box of sea) is two that share their
// ends, so that every edge of it is in one (an elevation boundary is a run of nodes, not
// a loop).
#include <cstdio>
#include <string>

#include "io/mesh_boundary.h"
#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

void write_fort14_file(const MeshView& v, const std::string& path, const std::string& what) {
  const QuadMesh& m = *v.data->mesh;
  const auto& depth = v.data->depth;
  const std::vector<std::array<int, 3>> triangles = quads_as_triangles(m);
  OutputFile f(path, what);
  std::FILE* raw = f.get();
  const char* xyz = v.geographic ? "%zu %.10f %.10f %.6f\n" : "%zu %.6f %.6f %.6f\n";
  // The title (ADCIRC's AGRID, of which it reads 80 characters) names the CRS at its end,
  // as hgrid.gr3's does, for isoquad to read back.
  std::fprintf(raw, "isoquad mesh (quads cut into triangles; depth in metres, positive down)%s\n",
               title_crs_note(v).c_str());
  std::fprintf(raw, "%zu %zu\n", triangles.size(), v.points.size());
  for (std::size_t i = 0; i < v.points.size(); ++i)
    std::fprintf(raw, xyz, i + 1, v.points[i].x, v.points[i].y, depth.empty() ? 0.0 : depth[i]);
  for (std::size_t e = 0; e < triangles.size(); ++e)
    std::fprintf(raw, "%zu 3 %d %d %d\n", e + 1, triangles[e][0] + 1, triangles[e][1] + 1,
                 triangles[e][2] + 1);

  std::vector<std::vector<int>> open;
  std::vector<const BoundarySegment*> land;
  for (const BoundarySegment& s : v.data->boundary.segments)
    if (s.kind == BoundaryKind::open) open.push_back(s.nodes);  // none closed
  for (const bool island : {false, true})
    for (const BoundarySegment& s : v.data->boundary.segments)
      if (s.kind == BoundaryKind::land && s.island == island) land.push_back(&s);
  auto count = [](const BoundarySegment& s) { return s.nodes.size() + (s.closed ? 1 : 0); };
  std::size_t total = 0;
  for (const auto& s : open) total += s.size();
  std::fprintf(raw, "%zu = Number of open boundaries\n", open.size());
  std::fprintf(raw, "%zu = Total number of open boundary nodes\n", total);
  for (std::size_t k = 0; k < open.size(); ++k) {
    std::fprintf(raw, "%zu 0 = Number of nodes for open boundary %zu\n", open[k].size(), k + 1);
    for (int n : open[k]) std::fprintf(raw, "%d\n", n + 1);
  }
  total = 0;
  for (const auto* s : land) total += count(*s);
  std::fprintf(raw, "%zu = Number of land boundaries\n", land.size());
  std::fprintf(raw, "%zu = Total number of land boundary nodes\n", total);
  for (std::size_t k = 0; k < land.size(); ++k) {
    std::fprintf(raw, "%zu %d = Number of nodes for land boundary %zu\n", count(*land[k]),
                 land[k]->island ? 21 : 20, k + 1);
    for (int n : land[k]->nodes) std::fprintf(raw, "%d\n", n + 1);
    if (land[k]->closed) std::fprintf(raw, "%d\n", land[k]->nodes.front() + 1);
  }
  f.close();
}

}  // namespace isoquad
