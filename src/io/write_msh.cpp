// Gmsh MSH 4.1 and 2.2 ASCII: one surface (the domain), one curve per boundary segment,
// physical groups land (1), open (2) and domain (3); or, open segment by segment,
// open_1, open_2... (11, 12...) instead of open. With --embed, a curve per path of edges
// on the lines, in the group embedded (4) (not among the surface's bounding curves).
// With --zones, a surface per zone instead, each in the physical group zone_N of tag N
// (a group of surfaces: the curves' tags are another dimension's), the quads in none
// in no_zone (the largest zone + 1). The quads' element tags are their numbers in the
// other formats (1 to the number of quads, whatever their zone); the lines' follow.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <string>

#include "core/error.h"
#include "io/mesh_formats.h"

namespace isoquad {

namespace {

constexpr int kLand = 1, kOpen = 2, kDomain = 3, kEmbedded = 4, kOpenSegments = 10;

// The physical group of each segment, and the groups' names by tag.
struct Groups {
  std::vector<int> of_segment;
  std::map<int, std::string> names;
};

Groups physical_groups(const std::vector<BoundarySegment>& segs, bool open_per_segment) {
  Groups g;
  int open = 0;
  for (const BoundarySegment& s : segs) {
    int tag = kLand;
    std::string name = "land";
    if (s.kind == BoundaryKind::open) {
      ++open;
      tag = open_per_segment ? kOpenSegments + open : kOpen;
      name = open_per_segment ? "open_" + std::to_string(open) : "open";
    }
    g.of_segment.push_back(tag);
    g.names[tag] = name;
  }
  return g;
}

// The edges (node pairs, 0-based) of a path.
std::vector<std::array<int, 2>> path_edges(const std::vector<int>& path) {
  std::vector<std::array<int, 2>> e;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) e.push_back({path[i], path[i + 1]});
  return e;
}

// The edges (node pairs, 0-based) of a segment.
std::vector<std::array<int, 2>> segment_edges(const BoundarySegment& s) {
  std::vector<std::array<int, 2>> e;
  for (std::size_t i = 0; i + 1 < s.nodes.size(); ++i) e.push_back({s.nodes[i], s.nodes[i + 1]});
  if (s.closed && s.nodes.size() > 1) e.push_back({s.nodes.back(), s.nodes.front()});
  return e;
}

struct Box {
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  void add(const Point2& p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
};

// The surfaces: their physical tags and names, and each quad's surface (0-based).
struct Surfaces {
  std::vector<int> tag;
  std::vector<std::string> name;
  std::vector<int> of_quad;
};

Surfaces surfaces(const std::vector<double>& zone, std::size_t num_quads, int domain_tag) {
  Surfaces s;
  if (zone.empty()) {
    s.tag = {domain_tag};
    s.name = {"domain"};
    s.of_quad.assign(num_quads, 0);
    return s;
  }
  std::map<long long, int> index;  // zone -> surface
  for (double z : zone) index[static_cast<long long>(z)] = 0;
  const long long none = index.rbegin()->first + 1;
  for (auto& [z, i] : index) {
    i = static_cast<int>(s.tag.size());
    s.tag.push_back(static_cast<int>(z == 0 ? none : z));
    s.name.push_back(z == 0 ? "no_zone" : "zone_" + std::to_string(z));
  }
  for (double z : zone) s.of_quad.push_back(index.at(static_cast<long long>(z)));
  return s;
}

}  // namespace

void write_msh_file(const MeshView& v, const std::string& path, const std::string& what,
                    const std::string& version, bool open_per_segment) {
  if (version != "4.1" && version != "2.2")
    throw Error(ErrorClass::usage, "options", "--msh-version must be 4.1 or 2.2");
  const QuadMesh& m = *v.data->mesh;
  const auto& segs = v.data->boundary.segments;
  std::ofstream f(path);
  f << std::setprecision(17);
  Groups groups = physical_groups(segs, open_per_segment);
  const auto& paths = v.data->embedded;
  if (!paths.empty()) groups.names[kEmbedded] = "embedded";
  f << "$MeshFormat\n" << version << " 0 8\n$EndMeshFormat\n";
  const Surfaces surf = surfaces(v.data->zone, m.quads.size(), kDomain);
  const std::size_t nsurf = surf.tag.size();
  f << "$PhysicalNames\n" << groups.names.size() + nsurf << "\n";
  for (const auto& [tag, name] : groups.names) f << "1 " << tag << " \"" << name << "\"\n";
  for (std::size_t k = 0; k < nsurf; ++k)
    f << "2 " << surf.tag[k] << " \"" << surf.name[k] << "\"\n";
  f << "$EndPhysicalNames\n";
  const std::size_t np = m.points.size(), nq = m.quads.size();
  std::size_t nl = 0;
  for (const auto& s : segs) nl += segment_edges(s).size();
  for (const auto& p : paths) nl += path_edges(p).size();
  // Curves 1.. the segments', then the paths'.
  const std::size_t ns = segs.size(), nc = ns + paths.size();
  if (version == "2.2") {
    f << "$Nodes\n" << np << "\n";
    for (std::size_t i = 0; i < np; ++i)
      f << i + 1 << " " << v.points[i].x << " " << v.points[i].y << " 0\n";
    f << "$EndNodes\n$Elements\n" << nl + nq << "\n";
    for (std::size_t i = 0; i < nq; ++i) {
      const auto& q = m.quads[i];
      const int s = surf.of_quad[i];
      f << i + 1 << " 3 2 " << surf.tag[s] << " " << s + 1 << " " << q[0] + 1 << " " << q[1] + 1
        << " " << q[2] + 1 << " " << q[3] + 1 << "\n";
    }
    std::size_t id = nq + 1;
    for (std::size_t c = 0; c < segs.size(); ++c)
      for (const auto& e : segment_edges(segs[c]))
        f << id++ << " 1 2 " << groups.of_segment[c] << " " << c + 1 << " " << e[0] + 1 << " "
          << e[1] + 1 << "\n";
    for (std::size_t k = 0; k < paths.size(); ++k)
      for (const auto& e : path_edges(paths[k]))
        f << id++ << " 1 2 " << kEmbedded << " " << ns + k + 1 << " " << e[0] + 1 << " " << e[1] + 1
          << "\n";
    f << "$EndElements\n";
  } else {
    Box all;
    for (const Point2& p : v.points) all.add(p);
    f << "$Entities\n0 " << nc << " " << nsurf << " 0\n";
    for (std::size_t c = 0; c < nc; ++c) {
      const std::vector<int>& nodes = c < ns ? segs[c].nodes : paths[c - ns];
      Box b;
      for (int n : nodes) b.add(v.points[n]);
      f << c + 1 << " " << b.x0 << " " << b.y0 << " 0 " << b.x1 << " " << b.y1 << " 0 1 "
        << (c < ns ? groups.of_segment[c] : kEmbedded) << " 0\n";
    }
    // The zones' surfaces list no bounding curves (the segments bound their union).
    for (std::size_t k = 0; k < nsurf; ++k) {
      f << k + 1 << " " << all.x0 << " " << all.y0 << " 0 " << all.x1 << " " << all.y1 << " 0 1 "
        << surf.tag[k] << " " << (nsurf == 1 ? segs.size() : 0);
      for (std::size_t c = 0; nsurf == 1 && c < segs.size(); ++c) f << " " << c + 1;
      f << "\n";
    }
    f << "$EndEntities\n";
    f << "$Nodes\n1 " << np << " 1 " << np << "\n2 1 0 " << np << "\n";
    for (std::size_t i = 0; i < np; ++i) f << i + 1 << "\n";
    for (std::size_t i = 0; i < np; ++i) f << v.points[i].x << " " << v.points[i].y << " 0\n";
    f << "$EndNodes\n";
    f << "$Elements\n" << nc + nsurf << " " << nl + nq << " 1 " << nl + nq << "\n";
    // A block per surface, its quads in their order, then a block per curve.
    for (std::size_t k = 0; k < nsurf; ++k) {
      const auto count = std::count(surf.of_quad.begin(), surf.of_quad.end(), static_cast<int>(k));
      f << "2 " << k + 1 << " 3 " << count << "\n";
      for (std::size_t i = 0; i < nq; ++i) {
        if (surf.of_quad[i] != static_cast<int>(k)) continue;
        const auto& q = m.quads[i];
        f << i + 1 << " " << q[0] + 1 << " " << q[1] + 1 << " " << q[2] + 1 << " " << q[3] + 1
          << "\n";
      }
    }
    std::size_t id = nq + 1;
    for (std::size_t c = 0; c < nc; ++c) {
      const auto edges = c < ns ? segment_edges(segs[c]) : path_edges(paths[c - ns]);
      f << "1 " << c + 1 << " 1 " << edges.size() << "\n";
      for (const auto& e : edges) f << id++ << " " << e[0] + 1 << " " << e[1] + 1 << "\n";
    }
    f << "$EndElements\n";
  }
  f.close();
  if (!f) throw Error(ErrorClass::output, "write", "'" + what + "': cannot write");
}

}  // namespace isoquad
