// --each and --each-clip on the command line: a region per value of an attribute over
// INPUT's features (or --clip's polygons), each with {} in its paths replaced by the
// value's file name, every output checked before any meshing, the regions run by
// run_regions (app/each_job.h) and the batch's table written as they end.
#pragma once

#include <string>

#include "cli_args.h"

namespace isoquad::cli {

// isoquad mesh --each FIELD (or --each-clip FIELD): run_mesh once per region.
int run_mesh_each(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m,
                  const std::string& command_line);
// isoquad quality --each FIELD: each region's mesh ({} in --mesh) measured against its
// fields.
int run_quality_each(const CommonArgs& a, const FieldArgs& f, const QualityArgs& q,
                     const std::string& command_line);

}  // namespace isoquad::cli
