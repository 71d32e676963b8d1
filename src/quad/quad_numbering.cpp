#include "quad/quad_numbering.h"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <cstdlib>
#include <numeric>
#include <utility>

namespace isoquad {

QuadNumbering reverse_cuthill_mckee(const QuadMesh& mesh) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  const int nv = static_cast<int>(mesh.points.size());
  // Each side once, from its smaller end, in a fixed order: the graph (and so the order)
  // depends on the mesh alone.
  std::vector<std::pair<int, int>> sides;
  sides.reserve(4 * mesh.quads.size());
  for (const auto& q : mesh.quads)
    for (int k = 0; k < 4; ++k) {
      const int a = q[k], b = q[(k + 1) % 4];
      sides.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  Graph graph(sides.begin(), sides.end(), static_cast<Graph::vertices_size_type>(nv));
  std::vector<Graph::vertex_descriptor> order(nv);
  boost::cuthill_mckee_ordering(graph, order.rbegin());
  QuadNumbering n;
  n.new_vertex.assign(nv, -1);
  for (int i = 0; i < nv; ++i) n.new_vertex[order[i]] = i;
  const int nq = static_cast<int>(mesh.quads.size());
  std::vector<int> quads(nq);
  std::iota(quads.begin(), quads.end(), 0);
  auto lowest = [&](int q) {
    const auto& c = mesh.quads[q];
    return std::min(std::min(n.new_vertex[c[0]], n.new_vertex[c[1]]),
                    std::min(n.new_vertex[c[2]], n.new_vertex[c[3]]));
  };
  std::stable_sort(quads.begin(), quads.end(), [&](int a, int b) { return lowest(a) < lowest(b); });
  n.new_quad.assign(nq, -1);
  for (int i = 0; i < nq; ++i) n.new_quad[quads[i]] = i;
  return n;
}

void renumber(QuadMesh& mesh, const QuadNumbering& numbering,
              const std::vector<std::vector<int>*>& vertex_lists) {
  const auto& nv = numbering.new_vertex;
  auto permuted = [&](auto& values) {
    if (values.size() != nv.size()) return;  // not kept (a mesh made by hand)
    auto out = values;
    for (std::size_t i = 0; i < values.size(); ++i) out[nv[i]] = values[i];
    values.swap(out);
  };
  permuted(mesh.points);
  permuted(mesh.chain);
  permuted(mesh.arc_m);
  permuted(mesh.fixed);
  std::vector<std::array<int, 4>> quads(mesh.quads.size());
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    auto& c = quads[numbering.new_quad[q]];
    for (int k = 0; k < 4; ++k) c[k] = nv[mesh.quads[q][k]];
  }
  mesh.quads.swap(quads);
  for (std::vector<int>* list : vertex_lists)
    for (int& v : *list)
      if (v >= 0) v = nv[v];
}

int vertex_bandwidth(const QuadMesh& mesh) {
  int widest = 0;
  for (const auto& q : mesh.quads)
    for (int k = 0; k < 4; ++k) widest = std::max(widest, std::abs(q[k] - q[(k + 1) % 4]));
  return widest;
}

}  // namespace isoquad
