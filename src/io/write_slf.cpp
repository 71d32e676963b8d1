// TELEMAC-2D geometry (Selafin, double precision: "SERAFIND") and boundary conditions
// (.cli). TELEMAC-2D computes on linear triangles only, so each quad is cut into two
// counter-clockwise triangles (quad_as_triangles). The geometry holds the variable
// BOTTOM (the bed level: minus the depth, 0 when unknown) at time 0, with --zones also
// FRIC_ID (each node's zone, node_zones: the friction zone TELEMAC-2D looks up in its
// FRICTION DATA FILE, instead of a ZONES FILE), and IPOBO, each boundary node's line in
// the .cli (0 inside). Records are Fortran sequential (a 4-byte length before and after),
// big-endian, TELEMAC's default.
//
// The .cli has a line per boundary node, 13 fields: LIHBOR LIUBOR LIVBOR HBOR UBOR VBOR
// AUBOR LITBOR TBOR ATBOR BTBOR N K, with 2 2 2 ... 2 (a wall) on land and 5 4 4 ... 4
// (prescribed elevation, free velocity and tracer) on the open boundary (an open
// segment's two end nodes included), N the node, K the line. The lines run as TELEMAC's
// manual asks: each outer contour counter-clockwise, then each island clockwise, each
// from its south-west node (the smallest x + y, then y), contours in that node's order.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

namespace {

struct CliNode {
  int node = 0;
  bool open = false;
};

// The boundary nodes in the .cli's order.
std::vector<CliNode> cli_order(const MeshView& v) {
  const MeshBoundary& b = v.data->boundary;
  const std::vector<Point2>& p = v.points;
  struct Contour {
    bool outer = true;
    std::size_t start = 0;  // its south-west node's place in the loop
    std::size_t loop = 0;
  };
  auto south_west = [&p](int a, int c) {
    const double sa = p[a].x + p[a].y, sc = p[c].x + p[c].y;
    return sa != sc ? sa < sc : p[a].y < p[c].y;
  };
  std::vector<Contour> contours;
  for (std::size_t l = 0; l < b.loops.size(); ++l) {
    const auto& loop = b.loops[l];
    double area2 = 0;
    const auto& m = v.data->mesh->points;  // the meshing CRS: orientation as meshed
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Point2 &a = m[loop[i]], &c = m[loop[(i + 1) % loop.size()]];
      area2 += a.x * c.y - c.x * a.y;
    }
    Contour k;
    k.outer = area2 > 0;
    k.loop = l;
    for (std::size_t i = 1; i < loop.size(); ++i)
      if (south_west(loop[i], loop[k.start])) k.start = i;
    contours.push_back(k);
  }
  std::stable_sort(contours.begin(), contours.end(), [&](const Contour& a, const Contour& c) {
    if (a.outer != c.outer) return a.outer;
    return south_west(b.loops[a.loop][a.start], b.loops[c.loop][c.start]);
  });
  std::vector<CliNode> order;
  for (const Contour& k : contours) {
    const auto& loop = b.loops[k.loop];
    const auto& kind = b.edge_kind[k.loop];
    const std::size_t n = loop.size();
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = (k.start + j) % n;
      const bool open =
          kind[i] == BoundaryKind::open || kind[(i + n - 1) % n] == BoundaryKind::open;
      order.push_back({loop[i], open});
    }
  }
  return order;
}

// Big-endian Fortran sequential records.
class RecordWriter {
 public:
  RecordWriter(const std::string& path, const std::string& what) : f_(path, what, "wb") {}
  void begin(std::size_t bytes) {
    bytes_ = static_cast<std::uint32_t>(bytes);
    u32(bytes_);
  }
  void end() { u32(bytes_); }
  void u32(std::uint32_t x) {
    const unsigned char b[4] = {static_cast<unsigned char>(x >> 24),
                                static_cast<unsigned char>(x >> 16),
                                static_cast<unsigned char>(x >> 8), static_cast<unsigned char>(x)};
    std::fwrite(b, 1, 4, f_.get());
  }
  void i32(int x) { u32(static_cast<std::uint32_t>(x)); }
  void f64(double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, 8);
    u32(static_cast<std::uint32_t>(u >> 32));
    u32(static_cast<std::uint32_t>(u));
  }
  void text(const std::string& s, std::size_t width) {
    std::string padded = s.substr(0, width);
    padded.resize(width, ' ');
    std::fwrite(padded.data(), 1, width, f_.get());
  }
  void ints(const std::vector<int>& xs) {
    begin(4 * xs.size());
    for (int x : xs) i32(x);
    end();
  }
  void doubles(const std::vector<double>& xs) {
    begin(8 * xs.size());
    for (double x : xs) f64(x);
    end();
  }
  void close() { f_.close(); }

 private:
  OutputFile f_;
  std::uint32_t bytes_ = 0;
};

// SCHISM's skewness of a triangle: its longest side over the radius of the circle of the
// same area.
double skewness(const QuadMesh& m, const std::array<int, 3>& t) {
  const Point2 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
  const double longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
  const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
  return longest / std::sqrt(area / M_PI);
}

}  // namespace

std::vector<double> node_zones(const QuadMesh& m, const std::vector<double>& quad_zone) {
  // Each node's quads' zones, as (node, zone) pairs sorted: runs of one node.
  std::vector<std::pair<int, double>> at;
  at.reserve(4 * m.quads.size());
  for (std::size_t q = 0; q < m.quads.size(); ++q)
    for (int n : m.quads[q]) at.emplace_back(n, quad_zone[q]);
  std::sort(at.begin(), at.end());
  std::vector<double> zone(m.points.size(), 0.0);
  for (std::size_t i = 0; i < at.size();) {
    std::size_t end = i;
    while (end < at.size() && at[end].first == at[i].first) ++end;
    // The zone of most of its quads; on a tie, a zone before none (0), then the smaller
    // number (the runs come by increasing number).
    double& best = zone[at[i].first];
    std::size_t best_count = 0;
    for (std::size_t j = i; j < end;) {
      std::size_t k = j;
      while (k < end && at[k].second == at[j].second) ++k;
      const double z = at[j].second;
      if (k - j > best_count || (k - j == best_count && best == 0 && z != 0)) {
        best = z;
        best_count = k - j;
      }
      j = k;
    }
    i = end;
  }
  return zone;
}

std::array<std::array<int, 3>, 2> quad_as_triangles(const QuadMesh& m, int q) {
  const auto& c = m.quads[q];
  const std::array<std::array<int, 3>, 2> a{{{c[0], c[1], c[2]}, {c[0], c[2], c[3]}}};
  const std::array<std::array<int, 3>, 2> b{{{c[1], c[2], c[3]}, {c[1], c[3], c[0]}}};
  return skewness(m, a[0]) + skewness(m, a[1]) <= skewness(m, b[0]) + skewness(m, b[1]) ? a : b;
}

std::vector<std::array<int, 3>> quads_as_triangles(const QuadMesh& m) {
  std::vector<std::array<int, 3>> out;
  out.reserve(2 * m.quads.size());
  for (int q = 0; q < static_cast<int>(m.quads.size()); ++q)
    for (const auto& t : quad_as_triangles(m, q)) out.push_back(t);
  return out;
}

void write_telemac_files(const MeshView& v, const std::string& path, const std::string& what,
                         const std::string& cli_path, const std::string& cli_what) {
  const QuadMesh& m = *v.data->mesh;
  const std::vector<CliNode> boundary = cli_order(v);
  const int np = static_cast<int>(v.points.size());
  std::vector<int> ipobo(np, 0);
  for (std::size_t k = 0; k < boundary.size(); ++k)
    ipobo[boundary[k].node] = static_cast<int>(k + 1);
  std::vector<int> ikle;
  for (const auto& t : quads_as_triangles(m))
    for (int n : t) ikle.push_back(n + 1);
  RecordWriter w(path, what);
  w.begin(80);
  w.text("isoquad " ISOQUAD_VERSION " mesh (quads cut into triangles)", 72);
  w.text("SERAFIND", 8);
  w.end();
  const bool zones = !v.data->zone.empty();
  w.ints({zones ? 2 : 1, 0});
  w.begin(32);
  w.text("BOTTOM", 16);
  w.text("M", 16);
  w.end();
  if (zones) {
    w.begin(32);
    w.text("FRIC_ID", 16);
    w.text("", 16);
    w.end();
  }
  // IPARAM: 1, then 0 for a whole mesh, not a partition (TELEMAC up to v6 reads a file
  // whose eighth is set as one partition of a parallel run, and its IPOBO record as the
  // nodes' global numbers).
  w.ints({1, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  w.ints({static_cast<int>(ikle.size() / 3), np, 3, 1});
  w.ints(ikle);
  w.ints(ipobo);
  std::vector<double> xs, ys, bottom(np, 0.0);
  for (const Point2& p : v.points) xs.push_back(p.x), ys.push_back(p.y);
  if (!v.data->depth.empty())
    for (int i = 0; i < np; ++i) bottom[i] = -v.data->depth[i] + 0.0;
  w.doubles(xs);
  w.doubles(ys);
  w.doubles({0.0});  // the time step's time
  w.doubles(bottom);
  if (zones) w.doubles(node_zones(m, v.data->zone));
  w.close();

  OutputFile f(cli_path, cli_what);
  for (std::size_t k = 0; k < boundary.size(); ++k) {
    const bool open = boundary[k].open;
    std::fprintf(f.get(), "%s 0.000 0.000 0.000 0.000 %d 0.000 0.000 0.000 %d %zu\n",
                 open ? "5 4 4" : "2 2 2", open ? 4 : 2, boundary[k].node + 1, k + 1);
  }
  f.close();
}

}  // namespace isoquad
