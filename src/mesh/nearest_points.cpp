#include "mesh/nearest_points.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_2.h>
#include <CGAL/Search_traits_adapter.h>

#include <algorithm>
#include <cmath>

namespace isoquad {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// The kd-tree holds indices; this map gives their points.
struct IndexPoint {
  using key_type = int;
  using value_type = K::Point_2;
  using reference = value_type;
  using category = boost::readable_property_map_tag;
  const std::vector<Point2>* points = nullptr;
  friend value_type get(const IndexPoint& map, int i) {
    const Point2& p = (*map.points)[i];
    return {p.x, p.y};
  }
};

using Traits = CGAL::Search_traits_adapter<int, IndexPoint, CGAL::Search_traits_2<K>>;
using Distance =
    CGAL::Distance_adapter<int, IndexPoint, CGAL::Euclidean_distance<CGAL::Search_traits_2<K>>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits, Distance>;

}  // namespace

struct NearestPoints::Tree {
  IndexPoint map;
  Search::Tree tree;
  Tree(const std::vector<Point2>& points, const std::vector<int>& ids)
      : map{&points}, tree(ids.begin(), ids.end(), Search::Tree::Splitter(), Traits(map)) {
    if (!ids.empty()) tree.build();  // (CGAL asserts on an empty tree's build)
  }
};

NearestPoints::NearestPoints(std::vector<Point2> points) : points_(std::move(points)) {
  std::vector<int> ids(points_.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
  tree_ = std::make_unique<Tree>(points_, ids);
}

NearestPoints::~NearestPoints() = default;

std::vector<std::pair<double, int>> NearestPoints::nearest(const Point2& p,
                                                           std::size_t count) const {
  std::vector<std::pair<double, int>> found;
  if (points_.empty() || count == 0) return found;
  const auto k = static_cast<unsigned int>(std::min(count, points_.size()));
  Search search(tree_->tree, K::Point_2(p.x, p.y), k, 0, true, Distance(tree_->map));
  for (const auto& [id, squared] : search) found.emplace_back(distance(points_[id], p), id);
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace isoquad
