// The whole pipeline (paper, Algorithm 1): front end, background mesh and fields,
// tiling, barycentric subdivision, smoothing and the convexity guarantee, quality.
#pragma once

#include <string>
#include <vector>

#include "app/fields_job.h"
#include "io/mesh_boundary.h"
#include "quad/embed_lines.h"
#include "quad/quad_mesh.h"
#include "quad/quad_quality.h"
#include "quad/smooth_quads.h"
#include "quad/subdivide_tiles.h"
#include "tiling/build_tiling.h"

namespace isoquad {

struct QuadZones;

struct VertexDepths;

struct MeshOptions {
  FieldsOptions fields;
  TilingParams tiling;
  SubdivideParams subdivide;
  SmoothParams smooth;
  // Tiling attempts (build_mesh: the sizes halved where the last one failed, or the
  // tiling's next variant) before giving up on a quad that smoothing cannot make
  // convex or a fold (--max-attempts). The Norwegian and Barents seas at 1:10m mesh in
  // the fourth; the Arctic Ocean north of 66 N at 1:10m folds at a new narrow channel in
  // each of ten (it needs a smaller --hmin).
  int max_attempts = 6;
  // After a failed attempt, the next one has sizes halved where it failed
  // (refinements_at), unless it failed at more places than this: then the failure is
  // not a local feature and the next tiling is the next variant.
  std::size_t max_refined_places = 16;
  // --embed: a path of edges moved onto each of --align's lines (embed_lines.h).
  bool embed_lines = false;
  EmbedParams embed;
  // --numbering rcm: the vertices in reverse Cuthill-McKee order and the quads after them
  // (quad_numbering.h); false (tiles): as the subdivision numbers them.
  bool renumber = true;
};

struct MeshResult {
  FieldsResult fields;
  TilingResult tiling;
  bool has_quads = false;  // false when the tiling stopped early (--stop-after)
  QuadMesh quads;
  QuadMetrics metrics;
  QualitySummary quality;
  SmoothStats smooth;
  EmbedStats embed;                        // with MeshOptions::embed_lines
  std::vector<EmbeddedPath> embedded;      // the paths of edges on the lines
  // --embed-points: the vertex of each of the front end's embed_points, and its target.
  std::vector<EmbeddedPoint> embedded_points;
  int attempts = 0;                        // tiling attempts made (see MeshOptions)
  std::vector<int> tiling_variants;        // the tiling variant of each attempt (build_mesh)
  std::vector<std::string> retry_reasons;  // why each earlier attempt was discarded
  std::vector<LocalRefinement> refinements;  // added after failed attempts (refinements_at)
};

// Local refinements at the places where an attempt failed (one per cluster of points
// within twice the local size h of each other): sizes at most h/2 within h of the place,
// graded beyond. A channel narrower than its quads, where the chord of one bank cuts
// the other bank's quads, then gets quads that fit it; a tile bent at a sharp corner,
// smaller tiles. Empty when the points make more than max_places places.
std::vector<LocalRefinement> refinements_at(const FieldsResult& fields, const std::vector<Point2>& points,
                                            std::size_t max_places);

// Throws Error(internal) rather than return a quad that is not strictly convex.
MeshResult build_mesh(const MeshOptions& options, const Progress& progress = Progress());

std::string format_mesh_summary(const MeshResult& r);
// The JSON report; with `boundary` (extract_boundary() of the quads, as the outputs
// have it), its open and land edges and segments too; with `depths`, how the vertices'
// depths were made; with `zones`, the quads in each zone; `more_stages` after the run's
// own (the writing of the outputs).
std::string mesh_report_json(const MeshResult& r, const std::string& command_line,
                             const MeshBoundary* boundary = nullptr,
                             const VertexDepths* depths = nullptr, const QuadZones* zones = nullptr,
                             const std::vector<StageTime>& more_stages = {});

}  // namespace isoquad
