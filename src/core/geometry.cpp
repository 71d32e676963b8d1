#include "core/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace isoquad {

std::array<double, 4> bounding_box(const std::vector<Point2>& points) {
  std::array<double, 4> b{1e300, 1e300, -1e300, -1e300};
  for (const Point2& q : points) {
    b[0] = std::min(b[0], q.x), b[1] = std::min(b[1], q.y);
    b[2] = std::max(b[2], q.x), b[3] = std::max(b[3], q.y);
  }
  return b;
}

std::array<double, 4> bounding_box(const Domain& domain) {
  std::array<double, 4> b{1e300, 1e300, -1e300, -1e300};
  for (const Polygon& p : domain.polygons) {
    const std::array<double, 4> r = bounding_box(p.outer);
    b = {std::min(b[0], r[0]), std::min(b[1], r[1]), std::max(b[2], r[2]), std::max(b[3], r[3])};
  }
  return b;
}

double signed_area(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return 0.0;
  // Shoelace relative to the first point, which keeps precision for large coordinates.
  const Point2 o = ring[0];
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double ax = ring[i].x - o.x, ay = ring[i].y - o.y;
    const double bx = ring[i + 1].x - o.x, by = ring[i + 1].y - o.y;
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

double polyline_length(const std::vector<Point2>& line) {
  double len = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) len += distance(line[i], line[i + 1]);
  return len;
}

double perimeter(const Ring& ring) {
  double len = 0.0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& a = ring[i];
    const Point2& b = ring[(i + 1) % n];
    len += std::hypot(b.x - a.x, b.y - a.y);
  }
  return len;
}

double area(const Polygon& polygon) {
  double a = std::abs(signed_area(polygon.outer));
  for (const Ring& h : polygon.holes) a -= std::abs(signed_area(h));
  return a;
}

double area(const Domain& domain) {
  double a = 0.0;
  for (const Polygon& p : domain.polygons) a += area(p);
  return a;
}

bool crosses_odd(const std::vector<Point2>& ring, const Point2& p) {
  bool odd = false;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const Point2 &a = ring[i], &b = ring[(i + 1) % n];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
      odd = !odd;
  }
  return odd;
}

EdgeBands::EdgeBands(const std::vector<Point2>& ring) : ring_(ring) {
  const std::size_t n = ring.size();
  if (n == 0) {
    start_.assign(2, 0);
    return;
  }
  y0_ = y1_ = ring[0].y;
  for (const Point2& p : ring) y0_ = std::min(y0_, p.y), y1_ = std::max(y1_, p.y);
  bands_ = std::max<std::size_t>(1, n / 8);
  start_.assign(bands_ + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 &a = ring[i], &b = ring[(i + 1) % n];
      for (std::size_t k = band(std::min(a.y, b.y)); k <= band(std::max(a.y, b.y)); ++k) {
        if (pass == 0)
          ++start_[k + 1];
        else
          sides_[fill[k]++] = i;
      }
    }
    if (pass == 0) {
      for (std::size_t k = 0; k < bands_; ++k) start_[k + 1] += start_[k];
      sides_.resize(start_[bands_]);
    }
  }
}

std::size_t EdgeBands::band(double y) const {
  if (y1_ <= y0_) return 0;
  const double t = (y - y0_) / (y1_ - y0_) * static_cast<double>(bands_);
  return std::min(bands_ - 1, static_cast<std::size_t>(std::max(0.0, t)));
}

std::pair<const std::size_t*, const std::size_t*> EdgeBands::sides_at(double y) const {
  if (ring_.empty() || y < y0_ || y > y1_) return {nullptr, nullptr};
  const std::size_t k = band(y);
  return {sides_.data() + start_[k], sides_.data() + start_[k + 1]};
}

bool EdgeBands::crosses_odd(const Point2& p) const {
  // crosses_odd's test, side by side, over the sides of p's band: a side that crosses
  // the ray has p.y between its ends' y, so it is listed there, once.
  bool odd = false;
  const std::size_t n = ring_.size();
  const auto [first, last] = sides_at(p.y);
  for (const std::size_t* s = first; s != last; ++s) {
    const Point2 &a = ring_[*s], &b = ring_[(*s + 1) % n];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
      odd = !odd;
  }
  return odd;
}

bool domain_contains(const Domain& domain, const Point2& p) {
  bool in = false;
  for (const Polygon& polygon : domain.polygons) {
    in ^= crosses_odd(polygon.outer, p);
    for (const Ring& hole : polygon.holes) in ^= crosses_odd(hole, p);
  }
  return in;
}

double distance_to_boundary(const Domain& domain, const Point2& p) {
  double best = std::numeric_limits<double>::infinity();
  for_each_side(domain, [&](const Point2& a, const Point2& b) {
    best = std::min(best, distance_to_segment(p, a, b));
  });
  return best;
}

double perimeter(const Polygon& polygon) {
  double len = perimeter(polygon.outer);
  for (const Ring& h : polygon.holes) len += perimeter(h);
  return len;
}

double perimeter(const Domain& domain) {
  double len = 0.0;
  for (const Polygon& p : domain.polygons) len += perimeter(p);
  return len;
}

std::size_t num_vertices(const Polygon& polygon) {
  std::size_t n = polygon.outer.size();
  for (const Ring& h : polygon.holes) n += h.size();
  return n;
}

std::size_t num_vertices(const Domain& domain) {
  std::size_t n = 0;
  for (const Polygon& p : domain.polygons) n += num_vertices(p);
  return n;
}

std::size_t num_holes(const Domain& domain) {
  std::size_t n = 0;
  for (const Polygon& p : domain.polygons) n += p.holes.size();
  return n;
}

void orient_polygon(Polygon& polygon) {
  if (signed_area(polygon.outer) < 0) std::reverse(polygon.outer.begin(), polygon.outer.end());
  for (Ring& h : polygon.holes)
    if (signed_area(h) > 0) std::reverse(h.begin(), h.end());
}

void start_at_lowest_vertex(Ring& ring) {
  const auto lowest = std::min_element(
      ring.begin(), ring.end(),
      [](const Point2& a, const Point2& b) { return a.y < b.y || (a.y == b.y && a.x < b.x); });
  std::rotate(ring.begin(), lowest, ring.end());
}

std::size_t remove_duplicates_and_spikes(Ring& ring) {
  const std::size_t before = ring.size();
  bool changed = true;
  while (changed && !ring.empty()) {
    changed = false;
    Ring out;
    out.reserve(ring.size());
    for (const Point2& p : ring)
      if (out.empty() || out.back() != p) out.push_back(p);
    while (out.size() > 1 && out.back() == out.front()) out.pop_back();
    // A spike: the ring goes a -> b -> a. Removing b and one copy of a keeps the area.
    const std::size_t n = out.size();
    if (n >= 3) {
      std::vector<bool> drop(n, false);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
        if (!drop[prev] && out[prev] == out[next]) {
          drop[i] = true;
          drop[next] = true;
          changed = true;
          break;  // one at a time keeps indices simple; spikes are rare
        }
      }
      if (changed) {
        Ring kept;
        for (std::size_t i = 0; i < n; ++i)
          if (!drop[i]) kept.push_back(out[i]);
        out.swap(kept);
      }
    }
    ring.swap(out);
  }
  return before - ring.size();
}

void remove_duplicates_and_spikes(std::vector<Polygon>& polygons) {
  for (Polygon& p : polygons) {
    remove_duplicates_and_spikes(p.outer);
    for (Ring& h : p.holes) remove_duplicates_and_spikes(h);
    p.holes.erase(
        std::remove_if(p.holes.begin(), p.holes.end(), [](const Ring& h) { return h.size() < 3; }),
        p.holes.end());
  }
  polygons.erase(std::remove_if(polygons.begin(), polygons.end(),
                                [](const Polygon& p) { return p.outer.size() < 3; }),
                 polygons.end());
}

std::string format_point(const Point2& p) {
  std::ostringstream os;
  os.precision(10);
  os << "(" << p.x << ", " << p.y << ")";
  return os.str();
}

void sort_by_area(std::vector<Polygon>& polygons) {
  std::stable_sort(polygons.begin(), polygons.end(), [](const Polygon& a, const Polygon& b) {
    const double aa = area(a), ab = area(b);
    if (aa != ab) return aa > ab;
    if (a.outer[0].x != b.outer[0].x) return a.outer[0].x < b.outer[0].x;
    return a.outer[0].y < b.outer[0].y;
  });
}

void normalize_polygons(std::vector<Polygon>& polygons) {
  remove_duplicates_and_spikes(polygons);
  for (Polygon& p : polygons) {
    orient_polygon(p);
    start_at_lowest_vertex(p.outer);
    for (Ring& h : p.holes) start_at_lowest_vertex(h);
  }
  sort_by_area(polygons);
}

Point2 nearest_on_segment(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return {a.x + t * dx, a.y + t * dy};
}

double distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 q = nearest_on_segment(p, a, b);
  return std::hypot(p.x - q.x, p.y - q.y);
}

PolylineIndex::PolylineIndex(std::vector<std::vector<Point2>> lines, std::vector<double> slack)
    : lines_(std::move(lines)), slack_(std::move(slack)) {
  constexpr int kRun = 32;
  slack_.resize(lines_.size(), 0.0);
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const auto& line = lines_[l];
    const int segments = static_cast<int>(line.size()) - 1;
    for (int first = 0; first < segments; first += kRun) {
      Run r;
      r.line = static_cast<int>(l);
      r.first = first;
      r.last = std::min(segments, first + kRun);
      r.xmin = r.xmax = line[first].x;
      r.ymin = r.ymax = line[first].y;
      for (int i = first + 1; i <= r.last; ++i) {
        r.xmin = std::min(r.xmin, line[i].x), r.xmax = std::max(r.xmax, line[i].x);
        r.ymin = std::min(r.ymin, line[i].y), r.ymax = std::max(r.ymax, line[i].y);
      }
      runs_.push_back(r);
    }
    max_slack_ = std::max(max_slack_, slack_[l]);
  }
  if (runs_.empty()) return;
  // About one run per cell, at most 256 x 256 cells.
  double x1 = runs_[0].xmax, y1 = runs_[0].ymax;
  x0_ = runs_[0].xmin, y0_ = runs_[0].ymin;
  for (const Run& r : runs_) {
    x0_ = std::min(x0_, r.xmin - slack_[r.line]), y0_ = std::min(y0_, r.ymin - slack_[r.line]);
    x1 = std::max(x1, r.xmax + slack_[r.line]), y1 = std::max(y1, r.ymax + slack_[r.line]);
  }
  const int n =
      static_cast<int>(std::clamp(std::sqrt(static_cast<double>(runs_.size())), 1.0, 256.0));
  cell_ = std::max({(x1 - x0_) / n, (y1 - y0_) / n, 1e-9});
  nx_ = std::max(1, static_cast<int>(std::ceil((x1 - x0_) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((y1 - y0_) / cell_)));
  auto range = [&](const Run& r, int& i0, int& i1, int& j0, int& j1) {
    const double w = slack_[r.line];
    i0 = std::clamp(static_cast<int>((r.xmin - w - x0_) / cell_), 0, nx_ - 1);
    i1 = std::clamp(static_cast<int>((r.xmax + w - x0_) / cell_), 0, nx_ - 1);
    j0 = std::clamp(static_cast<int>((r.ymin - w - y0_) / cell_), 0, ny_ - 1);
    j1 = std::clamp(static_cast<int>((r.ymax + w - y0_) / cell_), 0, ny_ - 1);
  };
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  int i0, i1, j0, j1;
  for (const Run& r : runs_) {
    range(r, i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) ++cell_start_[static_cast<std::size_t>(j) * nx_ + i + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_runs_.resize(cell_start_.back());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t k = 0; k < runs_.size(); ++k) {
    range(runs_[k], i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        cell_runs_[fill[static_cast<std::size_t>(j) * nx_ + i]++] = static_cast<int>(k);
  }
}

template <typename Visit>
void PolylineIndex::visit_near(const Point2& p, double tolerance, Visit visit) const {
  if (runs_.empty()) return;
  // The cells that a run within reach of p can meet.
  const double reach = tolerance + max_slack_;
  const double fx0 = (p.x - reach - x0_) / cell_, fx1 = (p.x + reach - x0_) / cell_;
  const double fy0 = (p.y - reach - y0_) / cell_, fy1 = (p.y + reach - y0_) / cell_;
  if (fx1 < 0 || fy1 < 0 || fx0 >= nx_ || fy0 >= ny_) return;
  const int i0 = std::max(0, static_cast<int>(fx0)), i1 = std::min(nx_ - 1, static_cast<int>(fx1));
  const int j0 = std::max(0, static_cast<int>(fy0)), j1 = std::min(ny_ - 1, static_cast<int>(fy1));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const Run& r = runs_[cell_runs_[k]];
        const double t = tolerance + slack_[r.line];
        if (p.x < r.xmin - t || p.x > r.xmax + t || p.y < r.ymin - t || p.y > r.ymax + t) continue;
        const auto& line = lines_[r.line];
        for (int s = r.first; s < r.last; ++s) {
          const double d = distance_to_segment(p, line[s], line[s + 1]);
          if (d <= t && !visit(r.line, s, d)) return;
        }
      }
    }
}

bool PolylineIndex::near(const Point2& p, double tolerance) const {
  bool found = false;
  visit_near(p, tolerance, [&found](int, int, double) { return !(found = true); });
  return found;
}

PolylineIndex::Nearest PolylineIndex::nearest(const Point2& p, double tolerance) const {
  Nearest best;
  best.distance = INFINITY;
  visit_near(p, tolerance, [&](int line, int segment, double d) {
    if (d < best.distance ||
        (d == best.distance && (line < best.line || (line == best.line && segment < best.segment))))
      best = {line, segment, d};
    return true;
  });
  return best;
}

std::vector<std::pair<int, int>> PolylineIndex::segments_near(const Point2& p,
                                                              double tolerance) const {
  std::vector<std::pair<int, int>> out;
  visit_near(p, tolerance, [&](int line, int segment, double) {
    out.emplace_back(line, segment);
    return true;
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool PolylineIndex::nearest_segment(const Point2& p, double tolerance, Point2& a, Point2& b) const {
  const Nearest n = nearest(p, tolerance);
  if (n.line < 0) return false;
  a = lines_[n.line][n.segment];
  b = lines_[n.line][n.segment + 1];
  return true;
}

}  // namespace isoquad
