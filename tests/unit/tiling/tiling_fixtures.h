// Fields for tiling tests: a domain with a constant size and the boundary-aligned or the
// axis-aligned cross field, corners tagged as the mesh job tags them.
#pragma once

#include "app/fields_job.h"
#include "mesh/boundary_corners.h"

namespace isoquad::test {

inline FieldsResult fields_on(const Domain& domain, double size_m, bool axis_cross) {
  FieldsOptions o;
  o.sizing.automatic = false;
  o.sizing.constant_m = size_m;
  if (axis_cross) {
    o.cross.source = CrossSource::constant;
    o.cross.angle_deg = 0.0;
  }
  FieldsResult f;
  build_fields_on_domain(domain, o, f);
  tag_corners(f.mesh, f.size, CornerParams());
  return f;
}

}  // namespace isoquad::test
