// Zones of a quad mesh (--zones): each quad takes the number of the first polygon, in
// the file's order, that holds its centroid: materials for SMS's .2dm, a cell value in
// the other outputs (a friction or a vegetation class, a region of a model).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "gis/crs.h"
#include "quad/quad_mesh.h"

namespace isoquad {

struct ZonesSource {
  std::string path, layer, field = "zone";  // --zones, --zones-layer, --zones-field
  bool given() const { return !path.empty(); }
};

struct QuadZones {
  std::vector<double> zone;                 // #Q: the zone's number, 0 in none
  std::map<long long, std::size_t> counts;  // quads by zone number (0: in none)
  std::size_t num_polygons = 0;
};

// Reads the polygons (read_size_features with FeatureValue::zone) and transforms them
// into `mesh_crs`. Throws Error(input), Error(usage) or Error(crs) as that reader does,
// and Error(crs) for a point that cannot be transformed.
std::vector<std::vector<std::vector<Point2>>> read_zone_polygons(const ZonesSource& source,
                                                                 const CrsInfo& mesh_crs,
                                                                 std::vector<double>* numbers);

// The zone of every quad of `mesh` (in `mesh_crs`).
QuadZones quad_zones(const ZonesSource& source, const CrsInfo& mesh_crs, const QuadMesh& mesh);

}  // namespace isoquad
