// Independent checks of ring geometry for the tests: do any two boundary segments of
// a domain cross or touch (other than consecutive segments at their shared vertex)?
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace isoquad::test {

namespace detail {
inline double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
inline bool on_segment(const Point2& a, const Point2& b, const Point2& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
// Closed-segment intersection (touching counts).
inline bool segments_meet(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
               o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}
}  // namespace detail

// Describes the first pair of meeting segments, or returns "" when there is none.
inline std::string find_crossing(const Domain& domain) {
  struct Seg {
    Point2 a, b;
    int ring;
    std::size_t index, ring_size;
    double xmin, xmax;
  };
  std::vector<Seg> segs;
  int ring_id = 0;
  for (const Polygon& p : domain.polygons) {
    std::vector<const Ring*> rings{&p.outer};
    for (const Ring& h : p.holes) rings.push_back(&h);
    for (const Ring* r : rings) {
      for (std::size_t i = 0; i < r->size(); ++i) {
        const Point2 a = (*r)[i], b = (*r)[(i + 1) % r->size()];
        segs.push_back({a, b, ring_id, i, r->size(), std::min(a.x, b.x), std::max(a.x, b.x)});
      }
      ++ring_id;
    }
  }
  std::sort(segs.begin(), segs.end(), [](const Seg& s, const Seg& t) { return s.xmin < t.xmin; });
  for (std::size_t i = 0; i < segs.size(); ++i) {
    for (std::size_t j = i + 1; j < segs.size() && segs[j].xmin <= segs[i].xmax; ++j) {
      const Seg &s = segs[i], &t = segs[j];
      if (s.ring == t.ring) {
        const std::size_t n = s.ring_size;
        const bool adjacent = (s.index + 1) % n == t.index || (t.index + 1) % n == s.index;
        if (adjacent) {
          // Consecutive segments share one vertex; they must not overlap beyond it.
          const bool s_first = (s.index + 1) % n == t.index;
          const Point2& far_of_t = s_first ? t.b : t.a;
          const Point2& far_of_s = s_first ? s.a : s.b;
          if (detail::orient(s.a, s.b, far_of_t) == 0 && detail::on_segment(s.a, s.b, far_of_t))
            return "ring " + std::to_string(s.ring) + " folds back at segment " +
                   std::to_string(t.index);
          if (detail::orient(t.a, t.b, far_of_s) == 0 && detail::on_segment(t.a, t.b, far_of_s))
            return "ring " + std::to_string(s.ring) + " folds back at segment " +
                   std::to_string(s.index);
          continue;
        }
      }
      if (detail::segments_meet(s.a, s.b, t.a, t.b))
        return "ring " + std::to_string(s.ring) + " segment " + std::to_string(s.index) +
               " meets ring " + std::to_string(t.ring) + " segment " + std::to_string(t.index);
    }
  }
  return "";
}

}  // namespace isoquad::test
