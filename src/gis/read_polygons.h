// Reading polygons from any OGR vector source (shapefile, GeoJSON, TopoJSON,
// GeoPackage...) with layer, attribute and bbox selection, and the checks a user needs
// to hear about: which file, which feature, what is wrong.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/geometry.h"
#include "gis/crs.h"

namespace isoquad {

struct ReadParams {
  std::string path;
  std::string layer;                        // empty: the only layer, or the first with polygons
  std::string where;                        // OGR SQL attribute filter (--where)
  std::optional<std::array<double, 4>> bbox;  // xmin, ymin, xmax, ymax (--bbox)
  std::string bbox_crs;                     // CRS of the bbox; empty: the source CRS
  // An area to read within instead of the bbox (--clip, read_clip_area): a ring in
  // bbox_crs (or the source CRS), its edges short enough to be taken as straight there.
  // It selects as the bbox does, and it is the ring a domain is cut by (bbox_ring).
  std::optional<Ring> clip;
  std::string clip_name;                    // how messages name it: "--clip 'aoi.gpkg'"
  std::string src_crs;                      // assigns the source CRS (overrides the file's)
  std::string default_crs;                  // the CRS of a file that has none (else an error)
  bool repair = false;                      // accept unclosed and degenerate rings, fixing them
  // A --bbox selection (without --where) that matches no polygon gives no polygons and a
  // warning instead of an error: the water domain of open sea is the whole bbox.
  bool empty_bbox_selection_ok = false;
  // Features that --where selects but none in the area of --bbox or --clip (or an area
  // that misses the layer's extent): no polygons, without an error (--exclude, where the
  // area holds none of its polygons).
  bool empty_area_ok = false;
  // A warning (SourceData::warnings) for the values --where compares a text attribute
  // with that no feature read holds, while others match; off for --each's regions, whose
  // filters add their own value (selection_values says it once).
  bool hint_unmatched_values = true;
  // A raster INPUT (read_raster_domain): the domain is where its values lie in
  // [zmin, zmax]; at least one is set. A window of more cells is read averaged.
  std::optional<double> zmin, zmax;
  std::size_t max_raster_cells = 16u << 20;
};

// One polygon of one feature, in the source CRS. rings[0] is the outer ring, the rest
// holes, all stored open. Orientation is not yet normalised.
struct SourcePolygon {
  long long fid = -1;
  int part = 0;  // index within a multipolygon
  std::vector<Ring> rings;
};

struct SourceData {
  std::vector<SourcePolygon> polygons;
  CrsInfo crs;
  std::string layer_name;
  // Without --layer, in a data set of several layers: the other layers of polygons.
  std::vector<std::string> other_polygon_layers;
  std::size_t num_features = 0;          // features read after selection
  std::size_t num_features_skipped = 0;  // features without a polygon geometry
  std::optional<Ring> bbox_ring;         // the bbox as a closed ring in the source CRS
  std::size_t num_points_removed = 0;    // duplicate points and spikes
  std::size_t num_rings_closed = 0;      // unclosed rings accepted with repair
  std::size_t num_rings_dropped = 0;     // degenerate rings dropped with repair
  // A layer of lines and no polygons: its closed lines, and its open lines joined end
  // to end, are the rings of the polygons (rings_from_lines).
  std::size_t num_line_features = 0;     // features with a line geometry
  std::size_t num_rings_from_lines = 0;  // rings the lines made
  std::size_t num_rings_joined = 0;      // of which made of two or more open lines
  std::size_t num_lines_joined = 0;      // the open lines in those
  // A raster INPUT: what was read of it (read_raster_domain).
  struct Raster {
    int columns = 0, rows = 0;            // of the raster
    int read_columns = 0, read_rows = 0;  // of the window read (after averaging)
    int averaged = 1;                     // cells averaged along each side (1: none)
    double cell_size_m = 0.0;             // the longer side of a cell read, in metres
    std::optional<double> zmin, zmax;
    std::size_t num_valid_cells = 0;          // with a value
    std::size_t num_cells_in_range = 0;       // of which in [zmin, zmax]
    double value_min = 0.0, value_max = 0.0;  // over the valid cells
  };
  std::optional<Raster> raster;
  std::vector<std::string> warnings;
};

// Reads the polygons of the selected layer and features; a layer of lines without
// polygons gives the polygons its lines' rings make (closed lines, and open lines
// joined where exactly two ends meet), nested by containment. Throws Error(input) for a
// missing, unreadable or empty source, Error(crs) for a missing or unusable CRS or
// coordinates outside its valid range, Error(usage) for a bad --where or --bbox.
SourceData read_polygons(const ReadParams& params);

// A value of an attribute over the selected features, with the OGR SQL filter that
// selects the features that have it.
struct SelectionValue {
  std::string text;    // as GDAL formats it; empty for null
  std::string filter;  // "field" = 'text' (or = text for a number), or "field" IS NULL
  bool null = false;   // the features without a value
  // The filter that selects exactly those features, by their ids (FID IN (...), or the
  // GeoPackage's FID column): OGR SQL's = ignores case on most formats ('Malta' would
  // also select 'MALTA'), and a real's or a date's text is not its stored value. The
  // readable `filter` when a feature has no id.
  std::string id_filter;
  std::size_t num_features = 0;  // the selected features that have it
  std::size_t num_polygons = 0;  // their polygons (a multi-polygon's parts each; lines none)
};

// The distinct values of `field` over the features `params` selects (layer, --where,
// --bbox), sorted (numbers by value), then null when some feature has no value. Throws as
// read_polygons, and Error(usage) for no such attribute (listing those there are).
// `unmatched`, when given: the values --where compares a text attribute with that no
// selected feature holds (where_hint's words), or empty.
std::vector<SelectionValue> selection_values(const ReadParams& params, const std::string& field,
                                             std::string* unmatched = nullptr);

// The area --clip (p.clip) or --bbox (p.bbox, one of them set) selects, as a ring in
// `crs` (from p.bbox_crs when given); `what` names it in messages ("--bbox 1,2,3,4").
// Throws Error(usage) for a bbox that is not one, Error(crs) when it cannot be
// transformed.
Ring selection_area(const ReadParams& p, const CrsInfo& crs, std::string& what);

// The bbox rectangle as a ring with `per_side` points per side, so that it bends
// correctly when projected.
Ring densified_box(const std::array<double, 4>& bbox, int per_side);

// An error of read_polygons on the file of an option other than INPUT (--clip,
// --exclude), named as that option: "--clip: ...", its --where as --clip-where.
Error read_error_of_option(const Error& e, const std::string& option);

// The area of --clip: the one polygon of a vector file (any format with a CRS), of its
// layer `layer` (empty: the first with polygons) and its features that `where` selects
// (OGR SQL; empty: all), without holes, its edges cut into pieces of at most 1/64 of its
// extent so that they stay straight in its CRS when transformed; `crs_wkt` its CRS.
// Error(input) for no polygon, several or a polygon with holes.
Ring read_clip_area(const std::string& path, const std::string& layer, const std::string& where,
                    std::string& crs_wkt);

}  // namespace isoquad
