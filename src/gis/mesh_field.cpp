#include "gis/mesh_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "core/error.h"
#include "gis/read_mesh.h"

namespace isoquad {

namespace {

ReadMesh read_values(const std::string& path, const std::string& what) {
  ReadMesh mesh = read_mesh(path);
  if (mesh.node_values.empty())
    throw Error(ErrorClass::input, "raster",
                what + " '" + path +
                    "': the mesh's nodes have no depths or bed levels to read (a .gr3, .ll or "
                    ".14 has depths, a .2dm or .mesh z, a .nc *_node_z, a .slf BOTTOM, on every "
                    "node)");
  return mesh;
}

}  // namespace

void check_mesh_field(const std::string& path, const std::string& what) {
  read_values(path, what);
}

MeshNodeField::MeshNodeField(const std::string& path, const std::string& what,
                             const CrsInfo& query_crs, const std::string& crs_if_none,
                             Values values, const std::optional<std::array<double, 4>>& extent) {
  ReadMesh mesh = values == Values::nodes ? read_values(path, what) : read_mesh(path);
  points_ = std::move(mesh.points);
  values_ = std::move(mesh.node_values);
  const std::string crs = !mesh.crs.empty() ? mesh.crs : crs_if_none;
  if (!crs.empty()) {
    const CrsTransform transform(
        parse_crs(crs, mesh.crs.empty() ? "--src-crs" : what + " '" + path + "' (its projection)"),
        query_crs);
    const long failed = transform.transform(points_);
    if (failed >= 0)
      throw Error(ErrorClass::crs, "raster",
                  what + " '" + path + "': node " + std::to_string(failed + 1) +
                      " cannot be transformed into the meshing CRS");
  }
  if (values == Values::element_sizes) {
    // Each side once (a side of two elements too), its length to both its ends.
    std::vector<std::array<int, 2>> sides;
    auto add = [&](const int* v, int k) {
      for (int i = 0; i < k; ++i)
        sides.push_back({std::min(v[i], v[(i + 1) % k]), std::max(v[i], v[(i + 1) % k])});
    };
    for (const auto& q : mesh.quads) add(q.data(), 4);
    for (const auto& t : mesh.triangles) add(t.data(), 3);
    std::sort(sides.begin(), sides.end());
    sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
    std::vector<double> sum(points_.size(), 0.0);
    std::vector<int> count(points_.size(), 0);
    for (const auto& s : sides) {
      const double length = distance(points_[s[0]], points_[s[1]]);
      for (int v : s) sum[v] += length, ++count[v];
    }
    values_.assign(points_.size(), 0.0);
    for (std::size_t v = 0; v < points_.size(); ++v)
      values_[v] = count[v] ? sum[v] / count[v] : 0.0;
  }
  triangles_ = std::move(mesh.triangles);
  for (const auto& q : mesh.quads) {
    const bool first =
        distance(points_[q[0]], points_[q[2]]) <= distance(points_[q[1]], points_[q[3]]);
    if (first) {
      triangles_.push_back({q[0], q[1], q[2]});
      triangles_.push_back({q[0], q[2], q[3]});
    } else {
      triangles_.push_back({q[1], q[2], q[3]});
      triangles_.push_back({q[1], q[3], q[0]});
    }
  }
  num_read_nodes_ = points_.size();
  if (extent) {  // the triangles whose boxes meet the extent's, widened; their nodes
    const auto& e = *extent;
    const double margin = 0.25 * std::max(e[2] - e[0], e[3] - e[1]);
    const double x0 = e[0] - margin, y0 = e[1] - margin, x1 = e[2] + margin, y1 = e[3] + margin;
    std::vector<int> node(points_.size(), -1);
    std::vector<Point2> points;
    std::vector<double> values;
    std::size_t kept = 0;
    for (const auto& t : triangles_) {
      double bx0 = points_[t[0]].x, by0 = points_[t[0]].y, bx1 = bx0, by1 = by0;
      for (int v : t) {
        bx0 = std::min(bx0, points_[v].x), bx1 = std::max(bx1, points_[v].x);
        by0 = std::min(by0, points_[v].y), by1 = std::max(by1, points_[v].y);
      }
      if (bx1 < x0 || bx0 > x1 || by1 < y0 || by0 > y1) continue;
      std::array<int, 3> renumbered{};
      for (int i = 0; i < 3; ++i) {
        int& n = node[t[i]];
        if (n < 0) {
          n = static_cast<int>(points.size());
          points.push_back(points_[t[i]]);
          values.push_back(values_[t[i]]);
        }
        renumbered[i] = n;
      }
      triangles_[kept++] = renumbered;
    }
    triangles_.resize(kept);
    points_ = std::move(points);
    values_ = std::move(values);
  }
  index_triangles();
}

MeshNodeField::MeshNodeField(std::vector<Point2> points, std::vector<double> values,
                             std::vector<std::array<int, 3>> triangles)
    : points_(std::move(points)), values_(std::move(values)), triangles_(std::move(triangles)) {
  index_triangles();
}

void MeshNodeField::index_triangles() {
  if (triangles_.empty()) {  // no element near the extent (none is kept without one)
    nx_ = ny_ = 0;
    return;
  }
  const std::array<double, 4> box = bounding_box(points_);
  const double width = std::max(box[2] - box[0], 1e-9), height = std::max(box[3] - box[1], 1e-9);
  // About one triangle a cell.
  cell_ =
      std::sqrt(width * height / static_cast<double>(std::max<std::size_t>(triangles_.size(), 1)));
  cell_ = std::max({cell_, width / 4096, height / 4096});
  x0_ = box[0];
  y0_ = box[1];
  nx_ = std::max(1, static_cast<int>(std::ceil(width / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(height / cell_)));
  auto cell_range = [&](const std::array<int, 3>& t) {
    double bx0 = points_[t[0]].x, by0 = points_[t[0]].y, bx1 = bx0, by1 = by0;
    for (int v : t) {
      bx0 = std::min(bx0, points_[v].x), bx1 = std::max(bx1, points_[v].x);
      by0 = std::min(by0, points_[v].y), by1 = std::max(by1, points_[v].y);
    }
    auto clamp_x = [&](double x) {
      return std::clamp(static_cast<int>((x - x0_) / cell_), 0, nx_ - 1);
    };
    auto clamp_y = [&](double y) {
      return std::clamp(static_cast<int>((y - y0_) / cell_), 0, ny_ - 1);
    };
    return std::array<int, 4>{clamp_x(bx0), clamp_y(by0), clamp_x(bx1), clamp_y(by1)};
  };
  std::vector<int> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (const auto& t : triangles_) {
    const auto r = cell_range(t);
    for (int j = r[1]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[2]; ++i) ++count[static_cast<std::size_t>(j) * nx_ + i + 1];
  }
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  cell_start_ = count;
  cell_triangles_.assign(count.back(), 0);
  for (int k = 0; k < static_cast<int>(triangles_.size()); ++k) {
    const auto r = cell_range(triangles_[k]);
    for (int j = r[1]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[2]; ++i)
        cell_triangles_[count[static_cast<std::size_t>(j) * nx_ + i]++] = k;
  }
  auto cell_of = [&](const Point2& p) {
    const int i = std::clamp(static_cast<int>((p.x - x0_) / cell_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((p.y - y0_) / cell_), 0, ny_ - 1);
    return static_cast<std::size_t>(j) * nx_ + i;
  };
  node_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (const Point2& p : points_) ++node_start_[cell_of(p) + 1];
  std::partial_sum(node_start_.begin(), node_start_.end(), node_start_.begin());
  std::vector<int> next(node_start_.begin(), node_start_.end() - 1);
  cell_nodes_.assign(points_.size(), 0);
  for (int v = 0; v < static_cast<int>(points_.size()); ++v)
    cell_nodes_[next[cell_of(points_[v])]++] = v;
}

double MeshNodeField::mean_over(const Point2& p, double half_width) const {
  const double at_p = sample(p);
  if (std::isnan(at_p) || !(half_width > 0)) return at_p;
  const double fx0 = std::floor((p.x - half_width - x0_) / cell_),
               fx1 = std::floor((p.x + half_width - x0_) / cell_),
               fy0 = std::floor((p.y - half_width - y0_) / cell_),
               fy1 = std::floor((p.y + half_width - y0_) / cell_);
  if (fx1 < 0 || fy1 < 0 || fx0 >= nx_ || fy0 >= ny_) return at_p;
  const int i0 = static_cast<int>(std::max(fx0, 0.0)),
            i1 = static_cast<int>(std::min(fx1, nx_ - 1.0));
  const int j0 = static_cast<int>(std::max(fy0, 0.0)),
            j1 = static_cast<int>(std::min(fy1, ny_ - 1.0));
  double sum = 0.0;
  int count = 0;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      for (int k = node_start_[c]; k < node_start_[c + 1]; ++k) {
        const Point2& q = points_[cell_nodes_[k]];
        if (std::abs(q.x - p.x) <= half_width && std::abs(q.y - p.y) <= half_width) {
          sum += values_[cell_nodes_[k]];
          ++count;
        }
      }
    }
  return count >= kMinAveraged ? sum / count : at_p;
}

std::string MeshNodeField::kept_text() const {
  if (num_read_nodes_ == 0 || points_.size() == num_read_nodes_) return "";
  return std::to_string(points_.size()) + " of its " + std::to_string(num_read_nodes_) +
         " nodes, those round the domain";
}

double MeshNodeField::max_value(const std::function<double(const Point2&)>& divisor) const {
  double v = 0.0;
  for (std::size_t i = 0; i < values_.size(); ++i)
    v = std::max(v, divisor ? values_[i] / divisor(points_[i]) : values_[i]);
  return v;
}

double MeshNodeField::sample(const Point2& p) const {
  if (nx_ == 0) return std::numeric_limits<double>::quiet_NaN();
  const double fx = (p.x - x0_) / cell_, fy = (p.y - y0_) / cell_;
  if (!(fx >= -1 && fy >= -1 && fx <= nx_ + 1 && fy <= ny_ + 1))
    return std::numeric_limits<double>::quiet_NaN();
  const int ci = std::clamp(static_cast<int>(std::floor(fx)), 0, nx_ - 1),
            cj = std::clamp(static_cast<int>(std::floor(fy)), 0, ny_ - 1);
  const std::size_t c = static_cast<std::size_t>(cj) * nx_ + ci;
  for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
    const auto& t = triangles_[cell_triangles_[k]];
    const Point2 &a = points_[t[0]], &b = points_[t[1]], &d = points_[t[2]];
    const double area = signed_area(a, b, d);
    if (area == 0) continue;
    const double wa = signed_area(p, b, d) / area, wb = signed_area(a, p, d) / area,
                 wd = signed_area(a, b, p) / area;
    constexpr double kSlack = -1e-9;  // a point on a shared side belongs to both
    if (wa >= kSlack && wb >= kSlack && wd >= kSlack)
      return wa * values_[t[0]] + wb * values_[t[1]] + wd * values_[t[2]];
  }
  // Off the mesh but within a cell of it (a vertex of a mesh whose boundary is a chord of
  // this one's, or simplified from it): the value at the nearest point of its boundary.
  double best = cell_, value = std::numeric_limits<double>::quiet_NaN();
  for (int j = std::max(cj - 1, 0); j <= std::min(cj + 1, ny_ - 1); ++j)
    for (int i = std::max(ci - 1, 0); i <= std::min(ci + 1, nx_ - 1); ++i) {
      const std::size_t cell = static_cast<std::size_t>(j) * nx_ + i;
      for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        const auto& t = triangles_[cell_triangles_[k]];
        for (int e = 0; e < 3; ++e) {
          const int u = t[e], w = t[(e + 1) % 3];
          const Point2 q = nearest_on_segment(p, points_[u], points_[w]);
          const double d = distance(p, q);
          if (d >= best) continue;
          const double length = distance(points_[u], points_[w]);
          const double s = length > 0 ? distance(points_[u], q) / length : 0.0;
          best = d;
          value = (1 - s) * values_[u] + s * values_[w];
        }
      }
    }
  return value;
}

}  // namespace isoquad
