// DHI MIKE 21/3 FM mesh (.mesh, text), as MIKE Zero's mesh tools and the FM engines read
// it: the header "100079 1000 N PROJECTION" (item bathymetry, unit metre, N nodes), a
// line per node "id x y z code" (z the bed level: minus the depth, 0 when unknown; code 0
// inside, 1 on land, 2, 3... on the open segments in hgrid.gr3's order, their end nodes
// included; where two open segments meet, the node takes the code of the one it ends), then "E 4
// 25" (E elements of at most 4 nodes, quadrilaterals present) and a line per quad "id n1 n2 n3 n4",
// counter-clockwise. MIKE makes a boundary face with a land node at either end land, and one
// between two open nodes open with its end node's code: so every face of an open segment, its first
// and last included, is open, and the faces next to it land. The projection is "LONG/LAT" (MIKE's
// name) for WGS 84 longitudes and latitudes, else the CRS as ESRI WKT.
#include <cstdio>

#include "gis/crs.h"
#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

void write_mike_mesh_file(const MeshView& v, const std::string& path, const std::string& what) {
  const QuadMesh& m = *v.data->mesh;
  const auto& depth = v.data->depth;
  const CrsInfo crs{v.crs_wkt, "'" + what + "': the CRS", v.geographic};
  const std::string projection = crs_is_wgs84_lonlat(crs) ? "LONG/LAT" : crs_esri_wkt(crs);
  std::vector<int> code(v.points.size(), 0);
  for (const BoundarySegment& s : v.data->boundary.segments)
    if (s.kind == BoundaryKind::land)
      for (int n : s.nodes) code[n] = 1;
  // A face takes its end node's code: each open segment's nodes but its first take its
  // code, and its first node too unless another open segment ends there (two segments
  // that meet: the node ends the one before along the boundary).
  int open_code = 1;
  std::vector<std::pair<int, int>> first_nodes;
  for (const BoundarySegment& s : v.data->boundary.segments)
    if (s.kind == BoundaryKind::open) {
      ++open_code;
      for (std::size_t i = 1; i < s.nodes.size(); ++i) code[s.nodes[i]] = open_code;
      if (!s.nodes.empty()) first_nodes.emplace_back(s.nodes.front(), open_code);
    }
  for (const auto& [n, c] : first_nodes)
    if (code[n] <= 1) code[n] = c;
  OutputFile f(path, what);
  std::fprintf(f.get(), "100079 1000 %zu %s\n", v.points.size(), projection.c_str());
  const char* node = v.geographic ? "%zu %.10f %.10f %.6f %d\n" : "%zu %.6f %.6f %.6f %d\n";
  for (std::size_t i = 0; i < v.points.size(); ++i)
    std::fprintf(f.get(), node, i + 1, v.points[i].x, v.points[i].y,
                 depth.empty() ? 0.0 : -depth[i] + 0.0, code[i]);
  std::fprintf(f.get(), "%zu 4 25\n", m.quads.size());
  for (std::size_t e = 0; e < m.quads.size(); ++e) {
    const auto& q = m.quads[e];
    std::fprintf(f.get(), "%zu %d %d %d %d\n", e + 1, q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
  }
  f.close();
}

}  // namespace isoquad
