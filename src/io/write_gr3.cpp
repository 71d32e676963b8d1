// SCHISM horizontal grid (hgrid.gr3 / hgrid.ll): nodes with depth (metres, positive
// down), elements (type 4 for quads), then the open boundary segments and the land
// boundary segments (flag 0 on the exterior boundary, 1 on an island) in SCHISM's layout.
#include <cstdio>

#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

void write_gr3_file(const MeshView& v, const std::vector<Point2>& points, const std::string& path,
                    const std::string& what) {
  const QuadMesh& m = *v.data->mesh;
  const auto& depth = v.data->depth;
  OutputFile f(path, what);
  std::FILE* raw = f.get();
  const char* xy = v.geographic ? "%zu %.10f %.10f %.6f\n" : "%zu %.6f %.6f %.6f\n";
  std::fprintf(raw, "isoquad mesh (depth in metres, positive down)\n");
  std::fprintf(raw, "%zu %zu\n", m.quads.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    std::fprintf(raw, xy, i + 1, points[i].x, points[i].y, depth.empty() ? 0.0 : depth[i]);
  for (std::size_t e = 0; e < m.quads.size(); ++e) {
    const auto& q = m.quads[e];
    std::fprintf(raw, "%zu 4 %d %d %d %d\n", e + 1, q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  }
  std::vector<const BoundarySegment*> open, land;
  for (const auto& s : v.data->boundary.segments)
    (s.kind == BoundaryKind::open ? open : land).push_back(&s);
  auto total = [](const std::vector<const BoundarySegment*>& ss) {
    std::size_t n = 0;
    for (const auto* s : ss) n += s->nodes.size();
    return n;
  };
  std::fprintf(raw, "%zu = Number of open boundaries\n", open.size());
  std::fprintf(raw, "%zu = Total number of open boundary nodes\n", total(open));
  for (std::size_t k = 0; k < open.size(); ++k) {
    std::fprintf(raw, "%zu = Number of nodes for open boundary %zu\n", open[k]->nodes.size(), k + 1);
    for (int n : open[k]->nodes) std::fprintf(raw, "%d\n", n + 1);
  }
  std::fprintf(raw, "%zu = Number of land boundaries\n", land.size());
  std::fprintf(raw, "%zu = Total number of land boundary nodes\n", total(land));
  for (std::size_t k = 0; k < land.size(); ++k) {
    std::fprintf(raw, "%zu %d = Number of nodes for land boundary %zu\n", land[k]->nodes.size(),
                 land[k]->island ? 1 : 0, k + 1);
    for (int n : land[k]->nodes) std::fprintf(raw, "%d\n", n + 1);
  }
  f.close();
}

}  // namespace isoquad
