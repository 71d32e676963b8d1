// The GIS front end shared by every subcommand: read -> select -> project -> clean ->
// simplify, from a vector file to a planar domain in metres.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/progress.h"
#include "domain/clean_domain.h"
#include "domain/narrow_features.h"
#include "domain/project_domain.h"
#include "domain/select_domain.h"
#include "domain/simplify_domain.h"
#include "domain/spike_tips.h"
#include "gis/map_scale.h"
#include "gis/read_polygons.h"

namespace isoquad {

struct FrontEndOptions {
  ReadParams read;
  // Polygons given instead of read from read.path, which then names them in messages
  // and the summary (`isoquad quality` without INPUT: the mesh's own outline). The
  // read's selections do not apply to them. They, and a mesh file's outline (read.path
  // a mesh: is_mesh_file), are meshed in their CRS when it is projected in metres and
  // project.dst_crs is empty.
  std::optional<SourceData> source;
  // With `source`, a mesh's outline: its open boundaries, as lines in its CRS (as a mesh
  // file given as INPUT has them).
  std::vector<std::vector<Point2>> source_open_lines;
  DomainKind kind = DomainKind::land;
  bool kind_given = false;  // --domain given (a raster INPUT's domain is set by its range)
  bool largest = false;
  ProjectParams project;
  // The smallest target element size in metres when known (0: unknown). It sets the
  // defaults of the two options below.
  double target_size_m = 0.0;
  // When set, derives target_size_m from the projected domain (the automatic sizing's
  // default scale from its area; ground sizes in the CRS's metres), in place of it.
  // `scale`: map_scale_for_domain's, or null.
  std::function<double(const Domain& domain, const MapScale* scale)> target_size_for_domain;
  // When set, the meshing CRS's scale over the projected domain where sizes are the
  // ground's (null where its metres are taken for the ground's): islands and holes are
  // then measured as at its smallest scale (CleanParams::area_factor).
  std::function<std::shared_ptr<const MapScale>(const Domain& domain)> map_scale_for_domain;
  // Warn when the automatic projection distorts lengths by more than 1% (off where the
  // sizes are the ground's: SizingParams::ground_sizes).
  bool warn_distortion = true;
  std::optional<double> simplify_m;          // default: target_size_m / 4, or off
  // How near the simplification may bring two parts of the boundary that were farther
  // apart (SimplifyParams::clearance_m). Default: the simplification's tolerance; 0: off.
  std::optional<double> simplify_clearance_m;
  std::optional<double> min_island_area_m2;  // default: target_size_m^2, or 0
  std::optional<double> min_width_m;         // default: target_size_m / 4, or off
  // Gaps and strips narrower than this are closed or cut out even where that changes the
  // topology (the hairline pass in build_planar_domain). Default: a fiftieth of
  // min_width, and only where the narrow features kept some piece for the topology.
  std::optional<double> hairline_m;
  // A vector file of lines (or polygons, by their rings) along the domain's edge: the
  // boundary they follow is open, the rest land, instead of a water domain's bbox.
  std::string open_boundary_path;
  std::string open_boundary_layer;  // empty: its first layer of lines, or its first layer
  // A vector file of one polygon, the area to mesh in place of a bbox (--clip): land
  // inside it, or water: it minus the polygons, its edge open where it is not land.
  std::string clip_path;
  std::string clip_layer;  // its layer (empty: the first with polygons)
  std::string clip_where;  // OGR SQL selecting its polygon among several
  // A vector file of polygons whose area is not meshed (--exclude): removed from the
  // domain, their edges land. In its CRS, else the INPUT's; only those in the area of
  // --bbox or --clip (else in the domain's box) are read.
  std::string exclude_path;
  std::string exclude_layer;  // its layer (empty: the only one, or the first with polygons)
  std::string exclude_where;  // OGR SQL selecting some of its features
  // With a Gmsh .msh as INPUT: its physical groups of curves (names or tags) that are
  // open; empty: those named "open..." (open_boundaries_from_groups).
  std::vector<std::string> open_groups;
  // A vector file of lines inside the domain that the cross field follows (--align).
  std::string align_path;
  std::string align_layer;  // empty: its first layer of lines, or its first layer
  // Whether a domain that none of the lines reaches is meshed (with a warning) rather
  // than stopped: --each, where one file of lines serves many regions. The same for
  // --embed-points.
  bool align_optional = false;
  // A vector file of points (its first layer of points) that the mesh gets vertices at
  // (--embed-points); in its CRS, else the INPUT's. Their names: the attribute
  // embed_points_name_field (--embed-points-name), else `name` when the layer has it.
  std::string embed_points_path;
  std::string embed_points_name_field;
};

// What the front end did, for the summary and the report.
struct DomainSummary {
  std::string input_path;
  std::string layer_name;
  std::vector<std::string> other_polygon_layers;  // SourceData's: not read (--layer)
  std::string source_crs_name;
  std::string meshing_crs_name;
  std::string meshing_crs_proj;  // PROJ string of the meshing CRS
  bool automatic_crs = false;
  bool input_crs_kept = false;     // the INPUT's projected CRS is the meshing CRS
  std::string input_crs_not_kept;  // why a projected INPUT's CRS was not (ProjectResult)
  std::optional<LocalProjection> local;
  std::size_t num_features = 0;
  std::size_t num_source_polygons = 0;
  std::size_t num_repaired = 0;
  std::size_t num_rings_closed = 0;
  std::size_t num_rings_dropped = 0;
  // A layer of lines read as the rings of polygons (SourceData's counts).
  std::size_t num_line_features = 0;
  std::size_t num_rings_from_lines = 0;
  std::size_t num_rings_joined = 0;
  std::size_t num_lines_joined = 0;
  std::size_t num_points_removed = 0;
  std::size_t num_components = 0;
  std::size_t num_rings = 0;
  std::size_t num_holes = 0;
  std::size_t num_vertices_before = 0;  // before simplification
  std::size_t num_vertices_after = 0;
  double area_m2 = 0.0;
  double perimeter_m = 0.0;
  double target_size_m = 0.0;  // 0: unknown
  double simplify_m = 0.0;
  double min_island_area_m2 = 0.0;
  double min_width_m = 0.0;
  double hairline_m = 0.0;
  NarrowResult narrow;
  SpikeResult spikes;  // tips sharper than SpikeParams::max_angle_deg cut back
  CleanResult dropped;
  // --open-boundary: the file, its lines, and the length of the domain's boundary
  // along them.
  std::string open_boundary_path;
  std::size_t open_boundary_num_lines = 0;
  double open_boundary_length_m = 0.0;
  // --exclude: the file, the polygons removed, those of them repaired, the area.
  std::string exclude_path;
  std::size_t exclude_num_polygons = 0;
  std::size_t exclude_num_repaired = 0;
  double exclude_area_removed_m2 = 0.0;
  // Of that, what the domain holds again after its cleaning and simplification, and the
  // areas that more than half of lies in it.
  double exclude_area_meshed_m2 = 0.0;
  std::size_t exclude_num_meshed = 0;
  // The boundary's open parts (FrontEndResult::open_boundary_parts): how many, how long.
  std::size_t num_open_parts = 0;
  double open_parts_length_m = 0.0;
  // --align: the file and its lines.
  std::string align_path;
  std::size_t align_num_lines = 0;
  // --embed-points: the file, its points, and how many lie inside the domain (the others
  // kept lie outside it within target_size_m of its boundary).
  std::string embed_points_path;
  std::size_t embed_points_read = 0;
  std::size_t embed_points_inside = 0;
  std::optional<SourceData::Raster> raster;  // a raster INPUT: what was read of it
  std::vector<std::string> warnings;
};

struct FrontEndResult {
  Domain domain;
  DomainSummary summary;
  // Polylines in the meshing CRS (a closed one repeats its first point), densified so
  // that they follow their projected segments: the lines of --open-boundary, or else
  // for a water domain its bbox. Boundary parts lying on them are the open (sea)
  // boundary; the rest is land. Empty for a land domain without --open-boundary.
  std::vector<std::vector<Point2>> open_boundary_lines;
  // By line: the line of --open-boundary (or of the mesh's open boundaries) it comes
  // from, 0 for the bbox's or the area's ring: where two meet, the mesh's open boundary
  // is two segments, one along each.
  std::vector<int> open_boundary_line_group;
  // How far the domain's boundary may lie from those lines where it follows them: the
  // simplification tolerance plus an allowance for the gap between a projected segment
  // and its chord (the domain's vertices are joined by chords): for the bbox, twice the
  // largest over its sides, included here; for --open-boundary, each segment's own, in
  // open_boundary_slack_m (one per line: each segment of the file gives two, its curved
  // image and its chord).
  double open_boundary_tolerance_m = 0.0;
  std::vector<double> open_boundary_slack_m;
  // How far, in edge lengths, a boundary edge's midpoint may lie from the lines beyond
  // that (extract_boundary's chord_share): 1% for the bbox's curved sides (its corners
  // are the mesh's corners); 20% for --open-boundary, whose lines may turn by up to 45
  // degrees (--corner-angle's default) at a vertex that the mesh's edges cut across.
  double open_boundary_chord_share = 0.01;
  // The lines of --align in the meshing CRS, densified as the open boundary's, where
  // they come near the domain's box: runs of their segments, and for each the index of
  // its line in the file.
  std::vector<std::vector<Point2>> align_lines;
  std::vector<int> align_line_of;
  // The points of --embed-points inside the domain or outside it within the target size
  // of its boundary, in the meshing CRS, in the file's order, and the number of each in
  // the file (from 1).
  std::vector<Point2> embed_points;
  std::vector<int> embed_point_number;
  std::vector<std::string> embed_point_name;  // each one's name; empty: the file has none
  // The domain's boundary where it is open, before meshing: runs of its edges whose
  // ends and middle lie on open_boundary_lines (within open_line_tolerance), each run a
  // polyline in the meshing CRS, the domain on its left; empty without open lines.
  std::vector<std::vector<Point2>> open_boundary_parts;
};

FrontEndResult build_planar_domain(const FrontEndOptions& options,
                                   const Progress& progress = Progress());

// The area of --clip (options.clip_path) into `read` (its ring, and its CRS as
// bbox_crs); nothing without --clip. Error(usage) with --bbox or --bbox-crs, or for
// --clip-layer or --clip-where without --clip; read_clip_area's errors.
void read_clip(const FrontEndOptions& options, ReadParams& read);

// open_boundary_tolerance_m plus the rounding of the lines' coordinates (1e-7 of their
// largest): the distance within which a point lies on the open boundary's lines, even
// where the tolerance is 0 (a mesh's outline, not simplified, and its open boundaries).
double open_line_tolerance(const FrontEndResult& result);

}  // namespace isoquad
