// The quality summary's lines and report values, shared by `isoquad mesh` (the mesh it
// made) and `isoquad quality` (a mesh read from a file).
#pragma once

#include <string>

#include "core/json_writer.h"
#include "quad/quad_quality.h"

namespace isoquad {

// What of the summary a mesh has: a mesh with triangles has its quads' shapes, sizes
// and orientations measured, not its vertices' regularity, its coast or its D-Flow FM
// links (which count the quads alone).
struct QualityParts {
  bool connectivity = true;  // regularity, coast, D-Flow FM
};

// "angles:", "size:" and "orientation:" lines.
std::string format_quad_shape_lines(const QualitySummary& q);
// "coast:", "regularity:", "SCHISM:" and "D-Flow FM:" lines (SCHISM's alone without
// parts.connectivity).
std::string format_quad_connectivity_lines(const QualitySummary& q, QualityParts parts = {});
// The quality object's values (the caller opens and closes it), without the counts of
// quads and vertices.
void add_quality_values(JsonWriter& j, const QualitySummary& q, QualityParts parts = {});

}  // namespace isoquad
