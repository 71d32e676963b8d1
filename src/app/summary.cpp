#include "app/summary.h"

#include <cstdio>
#include <sstream>

#include "app/versions.h"

namespace isoquad {

namespace {

std::string num(double v, int precision = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

}  // namespace

std::string format_domain_summary(const DomainSummary& s) {
  std::ostringstream os;
  if (s.raster) {
    const SourceData::Raster& r = *s.raster;
    os << "input:        " << s.input_path << " (raster, " << s.layer_name << ", " << r.columns
       << " x " << r.rows << " cells, CRS " << s.source_crs_name << ")\n";
    os << "contour:      " << r.num_cells_in_range << " of the " << r.num_valid_cells
       << " cells with a value in the area in [" << (r.zmin ? num(*r.zmin) : "-inf") << ", "
       << (r.zmax ? num(*r.zmax) : "inf") << "] (values " << num(r.value_min) << " to "
       << num(r.value_max) << "); " << s.num_source_polygons << " polygon(s) out of it\n";
  } else {
    os << "input:        " << s.input_path << " (layer '" << s.layer_name << "', " << s.num_features
       << " feature(s), " << s.num_source_polygons << " polygon(s), CRS " << s.source_crs_name
       << ")\n";
    if (!s.other_polygon_layers.empty()) {
      os << "              its first layer of polygons; the others (--layer):";
      for (std::size_t i = 0; i < s.other_polygon_layers.size(); ++i)
        os << (i ? ", '" : " '") << s.other_polygon_layers[i] << "'";
      os << "\n";
    }
  }
  os << "meshing CRS:  " << s.meshing_crs_name
     << (s.automatic_crs    ? " (automatic)"
         : s.input_crs_kept ? " (the input's)"
                            : "")
     << "\n";
  if (!s.input_crs_not_kept.empty())
    os << "              not the input's CRS: " << s.input_crs_not_kept << "\n";
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
  if (s.narrow.changed || s.narrow.num_pieces_kept) {
    os << "narrow:       " << s.narrow.num_pieces << " feature(s) under " << num(s.min_width_m)
       << " m wide changed: " << num(s.narrow.area_removed_m2 / 1e6, 4) << " km2 removed, "
       << num(s.narrow.area_added_m2 / 1e6, 4) << " km2 filled in";
    if (s.narrow.num_hairline)
      os << " (" << s.narrow.num_hairline << " hairline, whatever the topology)";
    if (s.narrow.num_pieces_kept)
      os << "; " << s.narrow.num_pieces_kept
         << " kept (changing them would cut or join components or holes)";
    os << "\n";
  }
  if (s.spikes.num_cut || s.spikes.num_cut_at_base) {
    os << "spikes:       " << s.spikes.num_cut + s.spikes.num_cut_at_base << " tip(s) sharper than "
       << num(SpikeParams{}.max_angle_deg) << " deg cut back to " << num(s.min_width_m) << " m wide";
    if (s.spikes.num_cut_at_base)
      os << " (" << s.spikes.num_cut_at_base << " narrower, at the base of a spit)";
    os << ": " << num(s.spikes.area_removed_m2 / 1e6, 4) << " km2 removed\n";
  }
  if (!s.exclude_path.empty()) {
    os << "excluded:     " << s.exclude_num_polygons << " polygon(s) of " << s.exclude_path << ": "
       << num(s.exclude_area_removed_m2 / 1e6, 6) << " km2 removed";
    if (s.exclude_num_repaired) os << " (" << s.exclude_num_repaired << " repaired)";
    os << "\n";
  }
  if (s.num_rings_from_lines) {
    os << "lines:        " << s.num_line_features << " feature(s) of lines made "
       << s.num_rings_from_lines << " ring(s)";
    if (s.num_rings_joined)
      os << " (" << s.num_rings_joined << " joined from " << s.num_lines_joined << " open lines)";
    os << ", " << s.num_source_polygons << " polygon(s)\n";
  }
  if (s.num_repaired || s.num_rings_closed || s.num_rings_dropped || s.num_points_removed)
    os << "repairs:      " << s.num_repaired << " invalid polygon(s) fixed, " << s.num_rings_closed
       << " ring(s) closed, " << s.num_rings_dropped << " degenerate ring(s) dropped, "
       << s.num_points_removed << " duplicate or spike point(s) removed\n";
  if (!s.open_boundary_path.empty())
    os << "open lines:   " << s.open_boundary_path << ": " << s.open_boundary_num_lines
       << " line(s), along " << num(s.open_boundary_length_m / 1e3, 6)
       << " km of the domain's boundary\n";
  if (s.num_open_parts > 0)
    os << "open parts:   " << s.num_open_parts << " run(s) of the boundary, "
       << num(s.open_parts_length_m / 1e3, 6) << " km, open (sea); the rest land\n";
  return os.str();
}

void add_domain_summary(JsonWriter& j, const DomainSummary& s) {
  j.value("input", s.input_path)
      .value("layer", s.layer_name)
      .array("other_polygon_layers", s.other_polygon_layers)
      .value("source_crs", s.source_crs_name)
      .value("meshing_crs", s.meshing_crs_name)
      .value("meshing_crs_proj", s.meshing_crs_proj)
      .value("automatic_crs", s.automatic_crs)
      .value("input_crs_kept", s.input_crs_kept)
      .value("input_crs_not_kept", s.input_crs_not_kept)
      .value("num_features", s.num_features)
      .value("num_source_polygons", s.num_source_polygons)
      .value("num_components", s.num_components)
      .value("num_rings", s.num_rings)
      .value("num_holes", s.num_holes)
      .value("num_vertices_before", s.num_vertices_before)
      .value("num_vertices_after", s.num_vertices_after)
      .value("area_m2", s.area_m2)
      .value("perimeter_m", s.perimeter_m)
      .value("simplify_m", s.simplify_m)
      .value("min_island_area_m2", s.min_island_area_m2)
      .value("min_width_m", s.min_width_m)
      .value("hairline_m", s.hairline_m)
      .value("narrow_area_removed_m2", s.narrow.area_removed_m2)
      .value("narrow_area_added_m2", s.narrow.area_added_m2)
      .value("narrow_num_changed", s.narrow.num_pieces)
      .value("narrow_num_kept", s.narrow.num_pieces_kept)
      .value("narrow_num_hairline", s.narrow.num_hairline)
      .value("spikes_num_cut", s.spikes.num_cut)
      .value("spikes_num_cut_at_base", s.spikes.num_cut_at_base)
      .value("spikes_area_removed_m2", s.spikes.area_removed_m2)
      .value("num_islands_dropped", s.dropped.num_islands_dropped)
      .value("num_holes_dropped", s.dropped.num_holes_dropped)
      .value("num_components_dropped", s.dropped.num_components_dropped)
      .value("num_repaired", s.num_repaired)
      .value("num_rings_closed", s.num_rings_closed)
      .value("num_points_removed", s.num_points_removed);
  if (!s.exclude_path.empty())
    j.value("exclude_path", s.exclude_path)
        .value("exclude_num_polygons", s.exclude_num_polygons)
        .value("exclude_num_repaired", s.exclude_num_repaired)
        .value("exclude_area_removed_m2", s.exclude_area_removed_m2)
        .value("exclude_area_meshed_m2", s.exclude_area_meshed_m2)
        .value("exclude_num_meshed", s.exclude_num_meshed);
  if (s.raster) {
    const SourceData::Raster& r = *s.raster;
    j.begin_object("raster");
    j.value("columns", r.columns)
        .value("rows", r.rows)
        .value("read_columns", r.read_columns)
        .value("read_rows", r.read_rows)
        .value("cells_averaged", r.averaged);
    if (r.zmin) j.value("zmin", *r.zmin);
    if (r.zmax) j.value("zmax", *r.zmax);
    j.value("num_valid_cells", r.num_valid_cells)
        .value("num_cells_in_range", r.num_cells_in_range)
        .value("value_min", r.value_min)
        .value("value_max", r.value_max);
    j.end_object();
  }
  if (s.num_rings_from_lines)
    j.value("num_line_features", s.num_line_features)
        .value("num_rings_from_lines", s.num_rings_from_lines)
        .value("num_rings_joined", s.num_rings_joined)
        .value("num_lines_joined", s.num_lines_joined);
  if (!s.open_boundary_path.empty())
    j.value("open_boundary", s.open_boundary_path)
        .value("open_boundary_num_lines", s.open_boundary_num_lines)
        .value("open_boundary_length_m", s.open_boundary_length_m);
  if (s.num_open_parts > 0)
    j.value("num_open_parts", s.num_open_parts).value("open_parts_length_m", s.open_parts_length_m);
  j.array("warnings", s.warnings);
}

std::string domain_summary_json(const DomainSummary& s) {
  JsonWriter j;
  j.begin_object();
  add_domain_summary(j, s);
  j.end_object();
  return j.str();
}

void add_report_header(JsonWriter& json, const std::string& command_line) {
  json.value("isoquad_version", ISOQUAD_VERSION).value("command_line", command_line);
  json.begin_object("libraries");
  for (const auto& [name, version] : library_versions()) json.value(name, version);
  json.end_object();
}

}  // namespace isoquad
