#include "app/quality_report.h"

#include <cpl_json.h>

#include "core/text.h"
#include "gis/gdal_env.h"

namespace isoquad {

std::string format_quad_shape_lines(const QualitySummary& q) {
  return printf_string(
             "angles:       %.1f%% in [75,105], min %.1f, max %.1f deg; eta mean %.3f, min %.3f\n",
             100 * q.share_angles_75_105, q.min_angle_deg, q.max_angle_deg, q.eta_mean, q.eta_min) +
         printf_string("size:         sqrt(area)/h median %.3f, %.1f%% in [0.8,1.25]\n",
                       q.size_ratio_median, 100 * q.share_size_08_125) +
         printf_string("orientation:  mean deviation %.2f deg, p90 %.2f deg\n",
                       q.orientation_mean_deg, q.orientation_p90_deg);
}

std::string format_align_line(const QualitySummary& q) {
  return printf_string(
      "along lines:  %zu quads within half their size of the --align lines, their edges %.2f "
      "deg off the lines on average\n",
      q.align_num_quads, q.align_deviation_mean_deg);
}

void add_align_values(JsonWriter& j, const QualitySummary& q) {
  j.value("align_num_quads", q.align_num_quads)
      .value("align_deviation_mean_deg", q.align_deviation_mean_deg);
}

std::string format_quad_connectivity_lines(const QualitySummary& q, QualityParts parts) {
  std::string out;
  if (parts.coast) {
    const double area_share = q.domain_area_m2 > 0 ? 100 * q.mesh_area_m2 / q.domain_area_m2 : 0.0;
    if (q.boundary_departure_max_h < 0.005)
      out += printf_string(
          "coast:        mesh area %.2f%% of the domain's; its boundary follows the domain's "
          "within 0.01 h%s\n",
          area_share,
          area_share > 101  ? " (so the area differs inside: elements overlap, or cover one "
                              "of the domain's holes)"
          : area_share < 99 ? " (so the area differs inside: elements with gaps between them)"
                            : "");
    else
      out += printf_string(
          "coast:        mesh area %.2f%% of the domain's; its boundary departs from the "
          "domain's by up to %.*f m (%.2f h, near %s), 95%% of its edges by %.2f h or less\n",
          area_share, q.boundary_departure_max_m >= 100 ? 0 : 2, q.boundary_departure_max_m,
          q.boundary_departure_max_h, format_point(q.boundary_departure_where).c_str(),
          q.boundary_departure_p95_h);
    if (q.num_boundary_backtracks > 0)
      out += printf_string(
          "              %zu boundary edge(s) run backwards along the domain's boundary "
          "(the mesh's boundary turns back over the coast there)\n",
          q.num_boundary_backtracks);
  }
  if (parts.connectivity) {
    std::size_t interior = 0;
    for (int n : q.interior_degree_histogram) interior += static_cast<std::size_t>(n);
    if (interior == 0)  // a mesh of a few quads round one boundary
      out +=
          printf_string("regularity:   no interior vertices; %.1f%% of boundary vertices regular\n",
                        100 * q.share_regular_boundary);
    else
      out += printf_string(
          "regularity:   %.1f%% of interior, %.1f%% of boundary, %.1f%% of all vertices "
          "regular\n",
          100 * q.share_regular_interior, 100 * q.share_regular_boundary,
          100 * q.share_regular_all);
  }
  if (parts.quads)
    out += printf_string(
        "SCHISM:       %zu quads with min/max angle < 0.5, %zu with aspect ratio > 5\n",
        q.schism_angle_ratio_violations, q.schism_aspect_violations);
  out += printf_string(
      "D-Flow FM:    orthogonality max %.3f, mean %.3f, %zu links over 0.5, %.1f%% at "
      "0.02 or less; smoothness max %.2f, %.1f%% of links at 1.2 or less\n",
      q.dflowfm_orthogonality_max, q.dflowfm_orthogonality_mean, q.dflowfm_orthogonality_violations,
      100 * q.dflowfm_share_orthogonality_002, q.dflowfm_smoothness_max,
      100 * q.dflowfm_share_smoothness_12);
  return out;
}

void add_quality_values(JsonWriter& j, const QualitySummary& q, QualityParts parts) {
  if (parts.quads)
    j.value("num_nonconvex", q.num_nonconvex)
        .value("share_angles_75_105", q.share_angles_75_105)
        .value("min_angle_deg", q.min_angle_deg)
        .value("max_angle_deg", q.max_angle_deg)
        .array("angle_histogram_5deg", q.angle_histogram)
        .value("size_ratio_median", q.size_ratio_median)
        .value("share_size_ratio_08_125", q.share_size_08_125)
        .array("size_ratio_histogram_005_from_025", q.size_ratio_histogram)
        .value("orientation_mean_deg", q.orientation_mean_deg)
        .value("orientation_p90_deg", q.orientation_p90_deg)
        .array("orientation_histogram_1deg", q.orientation_histogram)
        .value("eta_mean", q.eta_mean)
        .value("eta_min", q.eta_min)
        .value("schism_angle_ratio_violations", q.schism_angle_ratio_violations)
        .value("schism_aspect_ratio_violations", q.schism_aspect_violations)
        .value("schism_failures", q.schism_failures);
  j.value("dflowfm_orthogonality_max", q.dflowfm_orthogonality_max)
      .value("dflowfm_orthogonality_mean", q.dflowfm_orthogonality_mean)
      .value("dflowfm_orthogonality_violations", q.dflowfm_orthogonality_violations)
      .value("dflowfm_share_orthogonality_002", q.dflowfm_share_orthogonality_002)
      .value("dflowfm_smoothness_max", q.dflowfm_smoothness_max)
      .value("dflowfm_share_smoothness_12", q.dflowfm_share_smoothness_12)
      .value("mesh_area_m2", q.mesh_area_m2)
      .value("domain_area_m2", q.domain_area_m2);
  if (parts.connectivity)
    j.value("num_boundary_vertices", q.num_boundary_vertices)
        .value("num_boundary_crossings", q.num_boundary_crossings)
        .value("share_regular_interior", q.share_regular_interior)
        .value("share_regular_boundary", q.share_regular_boundary)
        .value("share_regular_all", q.share_regular_all)
        .array("interior_degree_histogram", q.interior_degree_histogram);
  if (!parts.coast) return;
  j.value("boundary_departure_max_m", q.boundary_departure_max_m)
      .value("boundary_departure_max_x_m", q.boundary_departure_where.x)
      .value("boundary_departure_max_y_m", q.boundary_departure_where.y)
      .value("boundary_departure_max_h", q.boundary_departure_max_h)
      .value("boundary_departure_p95_h", q.boundary_departure_p95_h)
      .value("num_boundary_backtracks", q.num_boundary_backtracks);
}

std::optional<QualitySummary> read_report_quality(const std::string& path) {
  CPLJSONDocument doc;
  {
    const GdalErrorCapture quiet;  // damaged or cut short: no figures (the caller says so)
    if (!doc.Load(path)) return std::nullopt;
  }
  const CPLJSONObject q = doc.GetRoot().GetObj("quality");
  if (!q.IsValid()) return std::nullopt;
  QualitySummary s;
  bool complete = true;
  // Each key's number into `out`; a key missing or not a number leaves the read incomplete.
  auto real = [&](const char* key, double& out) {
    const CPLJSONObject v = q.GetObj(key);
    const CPLJSONObject::Type type = v.IsValid() ? v.GetType() : CPLJSONObject::Type::Unknown;
    if (type == CPLJSONObject::Type::Double || type == CPLJSONObject::Type::Integer ||
        type == CPLJSONObject::Type::Long)
      out = v.ToDouble();
    else
      complete = false;
  };
  auto count = [&](const char* key, std::size_t& out) {
    double v = 0;
    real(key, v);
    out = static_cast<std::size_t>(v);
  };
  count("num_quads", s.num_quads);
  count("num_vertices", s.num_vertices);
  real("share_angles_75_105", s.share_angles_75_105);
  real("min_angle_deg", s.min_angle_deg);
  real("max_angle_deg", s.max_angle_deg);
  real("share_regular_interior", s.share_regular_interior);
  real("size_ratio_median", s.size_ratio_median);
  real("share_size_ratio_08_125", s.share_size_08_125);
  real("orientation_mean_deg", s.orientation_mean_deg);
  real("orientation_p90_deg", s.orientation_p90_deg);
  count("schism_angle_ratio_violations", s.schism_angle_ratio_violations);
  count("schism_aspect_ratio_violations", s.schism_aspect_violations);
  count("dflowfm_orthogonality_violations", s.dflowfm_orthogonality_violations);
  if (!complete) return std::nullopt;
  return s;
}

}  // namespace isoquad
