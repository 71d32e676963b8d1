// Background mesh, sizing field and cross field (paper, sections 2 and 2.2): the part
// of the pipeline shared by `isoquad fields` and `isoquad mesh`.
#pragma once

#include <string>
#include <vector>

#include "app/front_end.h"
#include "core/json_writer.h"
#include "core/stage_clock.h"
#include "fields/cross_field.h"
#include "fields/sizing_field.h"
#include "mesh/background_mesh.h"

namespace isoquad {

enum class CrossSource { boundary, constant, raster };

struct CrossParams {
  CrossSource source = CrossSource::boundary;
  double angle_deg = 0.0;    // --cross-angle
  std::string raster_path;   // --cross-raster: angles in degrees
  // --cross-conformal: the share of the conformal rotation J grad log h the boundary
  // field follows inside (boundary_aligned_cross_field). France automatic at about
  // 4,500 quads, 0 / 0.25 / 0.5 / 0.75 / 1: orientation 13.1 / 12.0 / 12.5 / 12.7 / 13.5
  // deg; Corsica automatic 10.4 / 10.2 / 9.2 / 9.1 deg, angles in range 86.5 / 87.0 /
  // 88.1 / 89.1%.
  double conformal = 0.5;
};

struct FieldsOptions {
  FrontEndOptions front;
  SizingParams sizing;
  CrossParams cross;
  // Background triangles are no longer than this fraction of the tile size 2h(x). The
  // paper uses 0.1; 0.15 measured the same quality on the square, annulus, Corsica,
  // Brittany water and France (within 2 points on every metric) in a third of the time,
  // and 0.2 again (within 2 points, the square still all quadrangles) in two thirds of
  // that: France automatic at about 4,500 quads 3.1 s -> 1.9 s. With the re-splitting
  // of pairs, 0.25 too (within a point on every sample but the square, which keeps 98%
  // quadrangle tiles instead of 100%), in 70% of the time of 0.2.
  double background_factor = 0.25;
  // The run stops (Error(usage)) before the background mesh when the sizes ask for more
  // quads than this (estimate_num_quads), and again before the cross field when the
  // background mesh predicts more (predicted_num_quads); 0: no limit. A mistyped size
  // (--size 10 for 10 km over France: 5 billion quads) otherwise fills the memory: a
  // quad costs about 2 to 5 KB at the peak (France at --size 700: 1,044,076 quads, 2.1 GB;
  // the Mediterranean at 1:10m with hmin 1 km, 90,121 quads, 436 MB).
  double max_quads = 1e6;
  // On a background mesh of more vertices than this, the boundary-aligned cross field is
  // solved on a coarser mesh of the domain (edges up to h, a quarter of the vertices)
  // and interpolated, the boundary's crosses kept exactly (0: never). Its sparse
  // Cholesky factorisation grows faster than the mesh: France at a uniform 1.5 km (1.8
  // million background vertices) 55.8 s and 2,177 MB -> 6.4 s and 1,107 MB, the whole run
  // 113 -> 70 s, the quads as good (98.3% of angles in range, orientation 3.84 degrees,
  // 2,053 under SCHISM's angle ratio; before 98.2%, 3.88, 2,148); the Mediterranean at
  // hmin 1 km (898,337) 768 -> 588 MB, 90.2% of angles in range either way. Below it
  // (every country at 1:10m, France automatic) nothing changes.
  std::size_t coarse_cross_above = 400000;
};

struct FieldsResult {
  FrontEndResult front;
  SizingSummary sizing;
  BackgroundMesh mesh;
  SizingField size;
  CrossField cross;
  std::vector<Singularity> singularities;
  // The vertices of the mesh the boundary-aligned field was solved on: the background
  // mesh's, or a coarser mesh's for a large one (FieldsOptions::coarse_cross_above); 0
  // for a constant field.
  std::size_t num_cross_solve_vertices = 0;
  // --align (the lines in front.align_lines): the background vertices fixed to them.
  std::size_t num_aligned_vertices = 0;
  std::vector<StageTime> times;
  // The depths the sizes read, kept when they hold scattered samples (soundings) or a
  // mesh, which a later attempt's sizes and the outputs' depths then share
  // (RasterStack's `share`).
  std::shared_ptr<const RasterStack> depths;
  // The meshing CRS's scale the sizes were multiplied by (SizingOracle::scale), null when
  // none was: the outputs' time steps measure the quads' widths on the ground with it.
  std::shared_ptr<const MapScale> scale;
};

// The front end's cleaning at the sizes `sizing` gives: its default scale hmin (or
// --size), in the CRS's metres at the smallest scale over the domain where the sizes
// are the ground's, and islands and holes measured as at that scale
// (FrontEndOptions::target_size_for_domain, map_scale_for_domain). `isoquad domain
// --size` so cleans as `mesh --size` does.
void clean_at_sizes(FrontEndOptions& front, const SizingParams& sizing);

// Front end, then the background mesh refined to the sizing, the sizing field on its
// vertices (graded), and the cross field.
FieldsResult build_fields(const FieldsOptions& options, const Progress& progress = Progress());

// Background mesh and fields for a domain already built (tests and benchmarks).
void build_fields_on_domain(const Domain& domain, const FieldsOptions& options,
                            FieldsResult& result, const Progress& progress = Progress());

std::string format_fields_summary(const FieldsResult& r);

// How many quads the sizes ask for, as the summary and the report say: the integral of
// 1 / h^2 over the domain (predicted_num_quads), but at least 3 per component, the
// fewest a mesh of one has (a tile of three sides); a domain smaller than its sizes
// would otherwise say "about 0 quads" and be meshed with 3 or 4.
double predicted_quads(const FieldsResult& r);

// The sizes at the background vertices on the ground: r.size in the CRS's metres divided
// by its scale where the sizes were multiplied by it (r.scale), else r.size itself. As
// the summary, the report and `isoquad fields`'s files give them.
SizingField ground_size_field(const FieldsResult& r);

// The report's sections on the fields, shared by `isoquad fields` and `isoquad mesh`:
// the values of the "sizing" object (the caller opens and closes it), the whole
// "background" and "cross_field" objects, and the "stages" array.
void add_sizing_report(JsonWriter& j, const FieldsResult& r);
void add_background_report(JsonWriter& j, const FieldsResult& r);
void add_stage_times(JsonWriter& j, const std::vector<StageTime>& times);

// `isoquad fields --report`: the version and command line, then "domain", "sizing",
// "background", "cross_field", "stages" and the peak memory, as in the mesh report.
std::string fields_report_json(const FieldsResult& r, const std::string& command_line);

}  // namespace isoquad
