#include "app/summary.h"

#include <cstdio>
#include <sstream>

namespace isoquad {

namespace {

std::string num(double v, int precision = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

}  // namespace

std::string format_domain_summary(const DomainSummary& s) {
  std::ostringstream os;
  os << "input:        " << s.input_path << " (layer '" << s.layer_name << "', " << s.num_features
     << " feature(s), " << s.num_source_polygons << " polygon(s), CRS " << s.source_crs_name
     << ")\n";
  os << "meshing CRS:  " << s.meshing_crs_name << (s.automatic_crs ? " (automatic)" : "") << "\n";
  if (!s.meshing_crs_proj.empty()) os << "              " << s.meshing_crs_proj << "\n";
  os << "domain:       " << s.num_components << " component(s), " << s.num_rings << " ring(s), "
     << s.num_holes << " hole(s)\n";
  os << "vertices:     " << s.num_vertices_before << " before simplification, "
     << s.num_vertices_after << " after (tolerance " << num(s.simplify_m) << " m)\n";
  os << "area:         " << num(s.area_m2 / 1e6, 8) << " km2\n";
  os << "perimeter:    " << num(s.perimeter_m / 1e3, 8) << " km\n";
  os << "dropped:      " << s.dropped.num_islands_dropped << " island(s) and "
     << s.dropped.num_holes_dropped << " hole(s) under " << num(s.min_island_area_m2) << " m2";
  if (s.dropped.num_components_dropped)
    os << ", " << s.dropped.num_components_dropped << " component(s) by --largest";
  os << "\n";
  if (s.num_repaired || s.num_rings_closed || s.num_rings_dropped || s.num_points_removed)
    os << "repairs:      " << s.num_repaired << " invalid polygon(s) fixed, " << s.num_rings_closed
       << " ring(s) closed, " << s.num_rings_dropped << " degenerate ring(s) dropped, "
       << s.num_points_removed << " duplicate or spike point(s) removed\n";
  return os.str();
}

std::string domain_summary_json(const DomainSummary& s) {
  std::ostringstream os;
  os << "{\n";
  os << "  \"input\": " << json_string(s.input_path) << ",\n";
  os << "  \"layer\": " << json_string(s.layer_name) << ",\n";
  os << "  \"source_crs\": " << json_string(s.source_crs_name) << ",\n";
  os << "  \"meshing_crs\": " << json_string(s.meshing_crs_name) << ",\n";
  os << "  \"meshing_crs_proj\": " << json_string(s.meshing_crs_proj) << ",\n";
  os << "  \"automatic_crs\": " << (s.automatic_crs ? "true" : "false") << ",\n";
  os << "  \"num_features\": " << s.num_features << ",\n";
  os << "  \"num_source_polygons\": " << s.num_source_polygons << ",\n";
  os << "  \"num_components\": " << s.num_components << ",\n";
  os << "  \"num_rings\": " << s.num_rings << ",\n";
  os << "  \"num_holes\": " << s.num_holes << ",\n";
  os << "  \"num_vertices_before\": " << s.num_vertices_before << ",\n";
  os << "  \"num_vertices_after\": " << s.num_vertices_after << ",\n";
  os << "  \"area_m2\": " << num(s.area_m2, 12) << ",\n";
  os << "  \"perimeter_m\": " << num(s.perimeter_m, 12) << ",\n";
  os << "  \"simplify_m\": " << num(s.simplify_m, 12) << ",\n";
  os << "  \"min_island_area_m2\": " << num(s.min_island_area_m2, 12) << ",\n";
  os << "  \"num_islands_dropped\": " << s.dropped.num_islands_dropped << ",\n";
  os << "  \"num_holes_dropped\": " << s.dropped.num_holes_dropped << ",\n";
  os << "  \"num_components_dropped\": " << s.dropped.num_components_dropped << ",\n";
  os << "  \"num_repaired\": " << s.num_repaired << ",\n";
  os << "  \"num_rings_closed\": " << s.num_rings_closed << ",\n";
  os << "  \"num_points_removed\": " << s.num_points_removed << ",\n";
  os << "  \"warnings\": [";
  for (std::size_t i = 0; i < s.warnings.size(); ++i)
    os << (i ? ", " : "") << json_string(s.warnings[i]);
  os << "]\n}\n";
  return os.str();
}

}  // namespace isoquad
