// SMS generic 2D mesh (.2dm), read by SMS, QGIS (MDAL) and the models that take SMS
// meshes: quads as E4Q cards (material 1, or each quad's zone: --zones), nodes as ND cards with z
// the elevation (minus the depth; 0 when unknown), then one nodestring (NS cards, ten nodes a card,
// the last negative) per boundary segment: the open segments first, then the land ones, each
// running with the domain on its left, as in hgrid.gr3. A whole loop of land (an island, a
// coast all round) is two nodestrings that share their ends: SMS does not allow one that
// begins and ends on the same node.
#include <fstream>
#include <iomanip>

#include "core/error.h"
#include "io/mesh_formats.h"

namespace isoquad {

namespace {

void write_nodestring(std::ofstream& f, const std::vector<int>& nodes) {
  std::vector<int> ids;
  for (int n : nodes) ids.push_back(n + 1);
  if (ids.size() < 2) return;
  ids.back() = -ids.back();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    f << (i % 10 == 0 ? "NS" : "") << " " << ids[i];
    if (i % 10 == 9 || i + 1 == ids.size()) f << "\n";
  }
}

}  // namespace

void write_2dm_file(const MeshView& v, const std::string& path, const std::string& what) {
  const QuadMesh& m = *v.data->mesh;
  const auto& depth = v.data->depth;
  std::ofstream f(path);
  f << "MESH2D\nNUM_MATERIALS_PER_ELEM 1\n";
  for (std::size_t e = 0; e < m.quads.size(); ++e) {
    const auto& q = m.quads[e];
    f << "E4Q " << e + 1 << " " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1
      << " " << (v.data->zone.empty() ? 1 : static_cast<long long>(v.data->zone[e])) << "\n";
  }
  f << std::fixed;
  for (std::size_t i = 0; i < v.points.size(); ++i)
    f << "ND " << i + 1 << " " << std::setprecision(v.geographic ? 10 : 6) << v.points[i].x << " "
      << v.points[i].y << " " << std::setprecision(6) << (depth.empty() ? 0.0 : -depth[i] + 0.0)
      << "\n";
  for (BoundaryKind kind : {BoundaryKind::open, BoundaryKind::land})
    for (const BoundarySegment& s : v.data->boundary.segments)
      if (s.kind != kind) {
        continue;
      } else if (s.closed && s.nodes.size() >= 3) {
        for (const std::vector<int>& half : loop_halves(s.nodes)) write_nodestring(f, half);
      } else {
        write_nodestring(f, s.nodes);
      }
  f.close();
  if (!f) throw Error(ErrorClass::output, "write", "'" + what + "': cannot write");
}

}  // namespace isoquad
