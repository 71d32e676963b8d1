#include "gis/rings_from_lines.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>

namespace isoquad {

namespace {

std::string feature_name(const SourceLine& line) {
  return "feature " + std::to_string(line.fid) +
         (line.part ? " part " + std::to_string(line.part) : std::string());
}

// A ring (stored open) with its sides in bands of y (EdgeBands), for "where does this
// point lie" queries in time proportional to the sides that cross the point's band.
class RingLocator {
 public:
  explicit RingLocator(const Ring& ring) : ring_(ring), bands_(ring) {}

  // 1 inside, 0 on the boundary, -1 outside.
  int locate(const Point2& p) const {
    const auto [first, last] = bands_.sides_at(p.y);
    if (first == last) return -1;
    const std::size_t n = ring_.size();
    bool inside = false;
    for (const std::size_t* s = first; s != last; ++s) {
      const Point2 &a = ring_[*s], &b = ring_[(*s + 1) % n];
      if (p == a || p == b) return 0;
      if ((a.y > p.y) != (b.y > p.y)) {
        const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        if (cross == 0.0) return 0;
        if ((cross > 0.0) == (b.y > a.y)) inside = !inside;
      } else if (a.y == p.y && b.y == p.y && std::min(a.x, b.x) <= p.x &&
                 p.x <= std::max(a.x, b.x)) {
        return 0;
      }
    }
    return inside ? 1 : -1;
  }

 private:
  const Ring& ring_;
  EdgeBands bands_;
};

// Whether `inner` lies inside the ring of `outer`, judged at its first vertex off that
// ring; false when every vertex is on it (the same ring twice).
bool holds(const RingLocator& outer, const Ring& inner) {
  for (const Point2& p : inner) {
    const int where = outer.locate(p);
    if (where != 0) return where > 0;
  }
  return false;
}

using Box = std::array<double, 4>;

bool box_holds(const Box& a, const Box& b) {
  return a[0] <= b[0] && a[1] <= b[1] && b[2] <= a[2] && b[3] <= a[3];
}

struct LineEnd {
  std::size_t line = 0;
  bool back = false;  // the line's last point, else its first
};

struct RingOfLines {
  Ring ring;
  std::size_t first_line = 0;
};

class RingBuilder {
 public:
  RingBuilder(const std::vector<SourceLine>& lines, std::string units)
      : lines_(lines), units_(std::move(units)) {}

  std::vector<RingOfLines> run(LineRings& out) {
    std::vector<RingOfLines> rings;
    std::vector<std::size_t> open;
    for (std::size_t l = 0; l < lines_.size(); ++l) {
      std::vector<Point2> pts = distinct(lines_[l].points);
      if (pts.size() < 2) continue;
      if (pts.size() >= 3 && pts.front() == pts.back()) {
        pts.pop_back();
        rings.push_back({std::move(pts), l});
      } else {
        cleaned_.emplace(l, std::move(pts));
        open.push_back(l);
      }
    }
    for (std::size_t l : open) {
      const auto& pts = cleaned_.at(l);
      ends_[key(pts.front())].push_back({l, false});
      ends_[key(pts.back())].push_back({l, true});
    }
    pair_ends();
    std::vector<bool> used(lines_.size(), false);
    for (std::size_t l : open) {
      if (used[l]) continue;
      RingOfLines r{cleaned_.at(l), l};
      used[l] = true;
      LineEnd at{l, true};
      std::size_t count = 1;
      for (;;) {
        const LineEnd next = partner_.at({at.line, at.back});
        if (next.line == l && !next.back) break;
        const auto& pts = cleaned_.at(next.line);
        if (next.back)
          r.ring.insert(r.ring.end(), pts.rbegin() + 1, pts.rend());
        else
          r.ring.insert(r.ring.end(), pts.begin() + 1, pts.end());
        used[next.line] = true;
        at = {next.line, !next.back};
        ++count;
      }
      r.ring.pop_back();  // the start point again
      if (count > 1) ++out.num_joined_rings, out.num_lines_joined += count;
      rings.push_back(std::move(r));
    }
    // A ring that passes a point twice (lines meeting four at a point, or a closed line
    // pinched) is cut there into rings that touch.
    std::vector<RingOfLines> cut;
    for (RingOfLines& r : rings)
      for (Ring& piece : split_where_touching(r.ring))
        cut.push_back({std::move(piece), r.first_line});
    return cut;
  }

  // The loops of a ring that passes some points more than once, each passing them once.
  static std::vector<Ring> split_where_touching(const Ring& ring) {
    std::vector<Ring> loops;
    Ring stack;
    std::map<Key, std::size_t> at;  // a point on the stack -> its position
    for (const Point2& p : ring) {
      const auto found = at.find(key(p));
      if (found == at.end()) {
        at.emplace(key(p), stack.size());
        stack.push_back(p);
        continue;
      }
      const std::size_t k = found->second;
      Ring loop(stack.begin() + static_cast<std::ptrdiff_t>(k), stack.end());
      for (std::size_t i = k + 1; i < stack.size(); ++i) at.erase(key(stack[i]));
      stack.resize(k + 1);
      if (loop.size() >= 3) loops.push_back(std::move(loop));
    }
    if (stack.size() >= 3) loops.push_back(std::move(stack));
    return loops;
  }

 private:
  using Key = std::pair<double, double>;
  static Key key(const Point2& p) { return {p.x, p.y}; }

  static std::vector<Point2> distinct(const std::vector<Point2>& points) {
    std::vector<Point2> out;
    for (const Point2& p : points)
      if (out.empty() || out.back() != p) out.push_back(p);
    return out;
  }

  // Each line end's partner: the other end where two meet; where four or more (an even
  // number) meet, the ends in turn round the point, in pairs, so that the rings touch
  // there without crossing.
  void pair_ends() {
    struct Loose {
      Point2 at;
      std::size_t line;
    };
    std::vector<Loose> loose;
    for (const auto& [at, ends] : ends_) {
      const Point2 p{at.first, at.second};
      if (ends.size() == 1) loose.push_back({p, ends[0].line});
      if (ends.size() > 2 && ends.size() % 2 != 0) {
        std::string names;
        for (const LineEnd& e : ends)
          names += (names.empty() ? "" : ", ") + feature_name(lines_[e.line]);
        throw LinesError(std::to_string(ends.size()) + " line ends meet at " + format_point(p) +
                         " (" + names + "): an odd number, where rings need two ends each");
      }
      if (ends.size() % 2 != 0) continue;
      std::vector<LineEnd> round = ends;
      std::stable_sort(round.begin(), round.end(), [&](const LineEnd& a, const LineEnd& b) {
        return turns_before(direction(a), direction(b));
      });
      for (std::size_t i = 0; i < round.size(); i += 2) {
        partner_[{round[i].line, round[i].back}] = round[i + 1];
        partner_[{round[i + 1].line, round[i + 1].back}] = round[i];
      }
    }
    if (loose.empty()) return;
    const Loose& first = loose.front();
    std::string message = feature_name(lines_[first.line]) + " ends at " + format_point(first.at) +
                          ", where no other line ends";
    const Loose* nearest = nullptr;
    for (const Loose& other : loose)
      if (other.line != first.line &&
          (!nearest || distance(first.at, other.at) < distance(first.at, nearest->at)))
        nearest = &other;
    if (nearest) {
      std::ostringstream gap;
      gap.precision(4);
      gap << distance(first.at, nearest->at);
      message += " (the nearest loose end of another line: " + feature_name(lines_[nearest->line]) +
                 "'s at " + format_point(nearest->at) + ", " + gap.str() + " " + units_ + " away)";
    }
    message += "; " + std::to_string(loose.size()) + " loose end(s) in all";
    throw LinesError(message);
  }

  // The direction in which a line leaves the point at its end.
  Point2 direction(const LineEnd& e) const {
    const auto& pts = cleaned_.at(e.line);
    const Point2 a = e.back ? pts[pts.size() - 1] : pts[0];
    const Point2 b = e.back ? pts[pts.size() - 2] : pts[1];
    return {b.x - a.x, b.y - a.y};
  }

  // Whether u comes before v counter-clockwise from the positive x axis.
  static bool turns_before(const Point2& u, const Point2& v) {
    const bool lower_u = u.y < 0 || (u.y == 0 && u.x < 0);
    const bool lower_v = v.y < 0 || (v.y == 0 && v.x < 0);
    if (lower_u != lower_v) return lower_v;
    return u.x * v.y - u.y * v.x > 0;
  }

  const std::vector<SourceLine>& lines_;
  std::string units_;
  std::map<std::size_t, std::vector<Point2>> cleaned_;  // the open lines, without repeated points
  std::map<Key, std::vector<LineEnd>> ends_;
  std::map<std::pair<std::size_t, bool>, LineEnd> partner_;
};

}  // namespace

LineRings rings_from_lines(const std::vector<SourceLine>& lines, const std::string& units) {
  LineRings out;
  std::vector<RingOfLines> rings = RingBuilder(lines, units).run(out);
  std::sort(rings.begin(), rings.end(),
            [](const RingOfLines& a, const RingOfLines& b) { return a.first_line < b.first_line; });
  const std::size_t n = rings.size();
  out.num_rings = n;
  std::vector<double> areas(n);
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    areas[i] = std::abs(signed_area(rings[i].ring));
    boxes[i] = bounding_box(rings[i].ring);
  }
  // Larger rings first; each ring's parent is the smallest larger ring that holds it.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return areas[a] > areas[b]; });
  std::vector<long> parent(n, -1);
  std::vector<int> depth(n, 0);
  std::map<std::size_t, RingLocator> locators;  // built for the rings tested as containers
  auto locator = [&](std::size_t j) -> const RingLocator& {
    auto it = locators.find(j);
    if (it == locators.end()) it = locators.emplace(j, RingLocator(rings[j].ring)).first;
    return it->second;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    for (std::size_t m = k; m-- > 0;) {
      const std::size_t j = order[m];
      if (areas[j] > areas[i] && box_holds(boxes[j], boxes[i]) &&
          holds(locator(j), rings[i].ring)) {
        parent[i] = static_cast<long>(j);
        depth[i] = depth[j] + 1;
        break;
      }
    }
  }
  std::vector<long> polygon_of(n, -1);
  std::map<long long, int> parts;
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 != 0) continue;
    const SourceLine& first = lines[rings[i].first_line];
    polygon_of[i] = static_cast<long>(out.polygons.size());
    SourcePolygon sp;
    sp.fid = first.fid;
    sp.part = parts[first.fid]++;
    sp.rings.push_back(rings[i].ring);
    out.polygons.push_back(std::move(sp));
  }
  for (std::size_t i = 0; i < n; ++i)
    if (depth[i] % 2 != 0) out.polygons[polygon_of[parent[i]]].rings.push_back(rings[i].ring);
  return out;
}

}  // namespace isoquad
