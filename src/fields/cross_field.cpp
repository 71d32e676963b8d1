#include "fields/cross_field.h"

#include <Eigen/Sparse>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "fields/cross_solve.h"

namespace isoquad {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kQuarterTurn = kPi / 2.0;
const char* const kStage = "cross field";

// Reduces an angle to the representative of its cross in [0, pi/2).
double reduce_cross_angle(double angle_rad) {
  double a = std::fmod(angle_rad, kQuarterTurn);
  if (a < 0.0) a += kQuarterTurn;
  if (a >= kQuarterTurn) a = 0.0;  // fmod rounding can land exactly on pi/2
  return a;
}

double cotangent(const Point2& apex, const Point2& a, const Point2& b) {
  const double ux = a.x - apex.x, uy = a.y - apex.y, vx = b.x - apex.x, vy = b.y - apex.y;
  return (ux * vx + uy * vy) / std::abs(ux * vy - uy * vx);
}

// An edge of the background mesh once, with its cotan weight (cot / 2 from each
// incident triangle, at least kMinWeight) and the rotation omega the field is asked to
// make from the lower vertex id to the higher.
struct CotanEdge {
  int lo, hi;
  double w, omega;
};

constexpr double kMinWeight = 1e-3;

// The edges in (lo, hi) order. omega is `conformal` times the integral of J grad log h
// (the rotation of a conformal grid with the sizes), averaged over the edge's triangles;
// 0 without sizes.
std::vector<CotanEdge> cotan_edges(const BackgroundMesh& mesh, const std::vector<double>& size_m,
                                   double conformal, bool connect) {
  const int num_triangles = static_cast<int>(mesh.triangles.size());
  std::vector<std::array<double, 2>> gradient(connect ? num_triangles : 0, {0.0, 0.0});
  for (int f = 0; f < static_cast<int>(gradient.size()); ++f) {
    const auto& t = mesh.triangles[f];
    const Point2 &p0 = mesh.points[t[0]], &p1 = mesh.points[t[1]], &p2 = mesh.points[t[2]];
    const double l0 = std::log(size_m[t[0]]), l1 = std::log(size_m[t[1]]) - l0,
                 l2 = std::log(size_m[t[2]]) - l0;
    const double ax = p1.x - p0.x, ay = p1.y - p0.y, bx = p2.x - p0.x, by = p2.y - p0.y;
    const double det = ax * by - ay * bx;
    if (det != 0.0) gradient[f] = {(l1 * by - l2 * ay) / det, (ax * l2 - bx * l1) / det};
  }
  // Triangle f's share of its edge opposite corner i.
  auto share = [&](int f, int i, double& w, double& omega) {
    const auto& t = mesh.triangles[f];
    const int a = t[(i + 1) % 3], b = t[(i + 2) % 3];
    w = 0.5 * cotangent(mesh.points[t[i]], mesh.points[a], mesh.points[b]);
    omega = 0.0;
    if (!connect) return;
    const Point2 &lo = mesh.points[std::min(a, b)], &hi = mesh.points[std::max(a, b)];
    omega = conformal * (gradient[f][0] * (hi.y - lo.y) - gradient[f][1] * (hi.x - lo.x));
  };
  std::vector<CotanEdge> edges;
  edges.reserve(3 * static_cast<std::size_t>(num_triangles) / 2 + mesh.points.size());
  for (int f = 0; f < num_triangles; ++f)
    for (int i = 0; i < 3; ++i) {
      const int g = mesh.neighbours[f][i];
      if (g >= 0 && g < f) continue;  // taken from g
      const auto& t = mesh.triangles[f];
      double w = 0.0, omega = 0.0;
      share(f, i, w, omega);
      int count = 1;
      if (g >= 0) {
        int j = 0;
        while (mesh.neighbours[g][j] != f) ++j;
        double wg = 0.0, omega_g = 0.0;
        share(g, j, wg, omega_g);
        w += wg;
        omega += omega_g;
        count = 2;
      }
      const int a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), std::max(w, kMinWeight), omega / count});
    }
  std::sort(edges.begin(), edges.end(), [](const CotanEdge& x, const CotanEdge& y) {
    return x.lo < y.lo || (x.lo == y.lo && x.hi < y.hi);
  });
  return edges;
}

// The matrix of the energy over the free vertices (`unknown`: vertex -> unknown or -1):
// `diagonal` on the diagonal, value(edge) at (a, b) and its conjugate at (b, a) for
// each edge between two unknowns a < b, filled column by column into reserved space.
template <typename Scalar, typename Value>
Eigen::SparseMatrix<Scalar> energy_matrix(const std::vector<CotanEdge>& edges,
                                          const std::vector<int>& unknown,
                                          const std::vector<double>& diagonal, Value value) {
  const int n = static_cast<int>(diagonal.size());
  Eigen::VectorXi per_column = Eigen::VectorXi::Ones(n);
  for (const CotanEdge& e : edges)
    if (unknown[e.lo] >= 0 && unknown[e.hi] >= 0)
      ++per_column[unknown[e.lo]], ++per_column[unknown[e.hi]];
  Eigen::SparseMatrix<Scalar> m(n, n);
  m.reserve(per_column);
  for (int i = 0; i < n; ++i) m.insert(i, i) = diagonal[i];
  for (const CotanEdge& e : edges) {
    const int ia = unknown[e.lo], ib = unknown[e.hi];
    if (ia < 0 || ib < 0) continue;
    const Scalar v = value(e);
    m.insert(ia, ib) = v;
    m.insert(ib, ia) = Eigen::numext::conj(v);
  }
  m.makeCompressed();
  return m;
}

}  // namespace

double cross_angle_of(double c, double s) {
  return reduce_cross_angle(std::atan2(s, c) / 4.0);
}

double cross_rotation_rad(double from_rad, double to_rad) {
  double d = std::fmod(to_rad - from_rad + kPi / 4.0, kQuarterTurn);
  if (d < 0.0) d += kQuarterTurn;
  return d - kPi / 4.0;
}

CrossField constant_cross_field(const BackgroundMesh& mesh, double angle_deg) {
  CrossField field;
  field.angle_rad.assign(mesh.points.size(), reduce_cross_angle(angle_deg * kPi / 180.0));
  return field;
}

FixedCrosses boundary_crosses(const BackgroundMesh& mesh) {
  const int num_vertices = static_cast<int>(mesh.points.size());
  // Sum of exp(4 i phi) over the two boundary edges of each chain vertex. Averaging in
  // 4-phi space keeps a 90-degree corner's cross aligned with both edges.
  std::vector<double> bc(num_vertices, 0.0), bs(num_vertices, 0.0);
  std::vector<char> is_boundary(num_vertices, 0);
  for (const BoundaryChain& chain : mesh.chains) {
    const std::size_t n = chain.vertices.size();
    for (std::size_t k = 0; k < n; ++k) {
      const int a = chain.vertices[k], b = chain.vertices[(k + 1) % n];
      const double phi = std::atan2(mesh.points[b].y - mesh.points[a].y,
                                    mesh.points[b].x - mesh.points[a].x);
      for (int v : {a, b}) {
        bc[v] += std::cos(4.0 * phi);
        bs[v] += std::sin(4.0 * phi);
        is_boundary[v] = 1;
      }
    }
  }
  // A vertex is fixed when its two edges agree on a cross; at a 45-degree (mod 90)
  // corner the sum vanishes and any cross is as good, so the vertex is left free.
  FixedCrosses b;
  b.is_fixed.assign(num_vertices, 0);
  b.uc.assign(num_vertices, 0.0);
  b.us.assign(num_vertices, 0.0);
  for (int v = 0; v < num_vertices; ++v) {
    const double norm = std::hypot(bc[v], bs[v]);
    if (!is_boundary[v] || norm < 1e-6) continue;
    b.is_fixed[v] = 1;
    b.uc[v] = bc[v] / norm;
    b.us[v] = bs[v] / norm;
  }
  return b;
}

CrossField boundary_aligned_cross_field(const BackgroundMesh& mesh,
                                        const std::vector<double>& size_m, double conformal,
                                        const FixedCrosses* lines) {
  const int num_vertices = static_cast<int>(mesh.points.size());
  FixedCrosses boundary = boundary_crosses(mesh);
  if (lines)
    for (int v = 0; v < num_vertices; ++v)
      if (lines->is_fixed[v] && !boundary.is_fixed[v]) {
        boundary.is_fixed[v] = 1;
        boundary.uc[v] = lines->uc[v];
        boundary.us[v] = lines->us[v];
      }
  const std::vector<char>& is_fixed = boundary.is_fixed;
  std::vector<double>& uc = boundary.uc;
  std::vector<double>& us = boundary.us;

  // Unknown numbering for free vertices.
  std::vector<int> unknown(num_vertices, -1);
  int num_unknowns = 0;
  for (int v = 0; v < num_vertices; ++v)
    if (!is_fixed[v]) unknown[v] = num_unknowns++;

  if (num_unknowns > 0) {
    // Cotan Laplacian, assembled per triangle: each edge gets cot(opposite angle) / 2
    // from each incident triangle. Interior edges of a Delaunay mesh have a
    // non-negative sum, but constrained (boundary-side) edges can be opposite an obtuse
    // angle; clamping to a small positive weight keeps the matrix an M-matrix, so the
    // solution obeys a maximum principle (no overshoot, |u| <= 1) and stays SPD (with
    // rotations, Hermitian positive definite).
    // Constant sizes ask for no rotation: the field is then exactly the smoothest one.
    const bool connect = conformal != 0.0 && size_m.size() == mesh.points.size() &&
                         std::adjacent_find(size_m.begin(), size_m.end(),
                                            std::not_equal_to<>()) != size_m.end();
    std::vector<CotanEdge> edges = cotan_edges(mesh, size_m, conformal, connect);
    using Complex = std::complex<double>;
    Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(num_unknowns);
    std::vector<double> diagonal(num_unknowns, 0.0);
    for (const CotanEdge& e : edges) {
      // u_b ~ r u_a with r = exp(4 i omega): the energy w |u_b - r u_a|^2 puts
      // -w conj(r) at (a, b) and -w r at (b, a).
      const Complex r = std::polar(1.0, 4.0 * e.omega);
      const int ia = unknown[e.lo], ib = unknown[e.hi];
      if (ia >= 0) diagonal[ia] += e.w;
      if (ib >= 0) diagonal[ib] += e.w;
      if (ia >= 0 && ib < 0) rhs(ia) += e.w * std::conj(r) * Complex(uc[e.hi], us[e.hi]);
      if (ib >= 0 && ia < 0) rhs(ib) += e.w * r * Complex(uc[e.lo], us[e.lo]);
    }
    // The real Laplacian (no rotations), factorised first; with rotations the complex
    // Hermitian matrix of the energy, built only then (the two and the factor are most
    // of the memory on large domains). Without rotations the real and imaginary parts
    // decouple: one real factorisation, two right-hand sides.
    auto laplacian =
        energy_matrix<double>(edges, unknown, diagonal, [](const CotanEdge& e) { return -e.w; });
    std::function<Eigen::SparseMatrix<Complex>()> hermitian;
    if (connect)
      hermitian = [&] {
        auto h = energy_matrix<Complex>(edges, unknown, diagonal, [](const CotanEdge& e) {
          return -e.w * std::conj(std::polar(1.0, 4.0 * e.omega));
        });
        std::vector<CotanEdge>().swap(edges);
        return h;
      };
    else
      std::vector<CotanEdge>().swap(edges);
    const Eigen::VectorXcd u = solve_cross_system(std::move(laplacian), hermitian, rhs);
    for (int v = 0; v < num_vertices; ++v) {
      if (unknown[v] < 0) continue;
      uc[v] = u(unknown[v]).real();
      us[v] = u(unknown[v]).imag();
    }
  }

  CrossField field;
  field.angle_rad.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v) field.angle_rad[v] = cross_angle_of(uc[v], us[v]);
  return field;
}

std::vector<Singularity> cross_field_singularities(const BackgroundMesh& mesh,
                                                   const CrossField& field) {
  if (field.angle_rad.size() != mesh.points.size())
    throw Error(ErrorClass::internal, kStage, "the cross field does not match the mesh");
  std::vector<Singularity> singularities;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    double turn = 0.0;
    for (int i = 0; i < 3; ++i)
      turn += cross_rotation_rad(field.angle_rad[t[i]], field.angle_rad[t[(i + 1) % 3]]);
    // The sum is a multiple of pi/2 up to rounding.
    const int quarters = static_cast<int>(std::lround(turn / kQuarterTurn));
    if (quarters == 0) continue;
    const Point2 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    singularities.push_back(
        {static_cast<int>(f), quarters, {(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0}});
  }
  return singularities;
}

double cross_angle_at(const BackgroundMesh& mesh, const CrossField& field, int triangle,
                      const std::array<double, 3>& bary) {
  const auto& t = mesh.triangles.at(triangle);
  double c = 0.0, s = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double a4 = 4.0 * field.angle_rad[t[i]];
    c += bary[i] * std::cos(a4);
    s += bary[i] * std::sin(a4);
  }
  return cross_angle_of(c, s);
}

}  // namespace isoquad
