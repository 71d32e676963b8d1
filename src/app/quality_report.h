// The quality summary's lines and report values, shared by `isoquad mesh` (the mesh it
// made) and `isoquad quality` (a mesh read from a file).
#pragma once

#include <optional>
#include <string>

#include "core/json_writer.h"
#include "quad/quad_quality.h"

namespace isoquad {

// What of the summary a mesh has: a mesh with triangles has its quads' shapes, sizes
// and orientations measured and its D-Flow FM links (between any two cells), not its
// vertices' regularity or its coast (the quads' own boundary runs round the triangles).
struct QualityParts {
  bool quads = true;         // the quads' angles, sizes, orientation, SCHISM's checks
  bool connectivity = true;  // the quads' regularity
  bool coast = true;         // the boundary's departure from the domain's
};

// "angles:", "size:" and "orientation:" lines.
std::string format_quad_shape_lines(const QualitySummary& q);
// "along lines:" (with --align: measure_line_following's figures).
std::string format_align_line(const QualitySummary& q);
void add_align_values(JsonWriter& j, const QualitySummary& q);
// "coast:" (with parts.coast), "regularity:" (with parts.connectivity), "SCHISM:" (with
// parts.quads) and "D-Flow FM:" lines.
std::string format_quad_connectivity_lines(const QualitySummary& q, QualityParts parts = {});
// The quality object's values (the caller opens and closes it), without the counts of
// quads and vertices, those of `parts` and D-Flow FM's.
void add_quality_values(JsonWriter& j, const QualitySummary& q, QualityParts parts = {});

// The figures of --each's table read back from a report (--report FILE.json) an earlier
// run wrote: its quality object's counts and shares; nothing when the file cannot be read
// or lacks one of them.
std::optional<QualitySummary> read_report_quality(const std::string& path);

}  // namespace isoquad
