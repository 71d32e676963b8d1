// A mesh's node values as a field (an ocean model's grid as a depth source: the depths
// of the hgrid.gr3 a model runs on now, for the mesh that replaces it).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/crs.h"
#include "gis/raster_field.h"

namespace isoquad {

// Linear over each triangle (a quadrangle cut along its shorter diagonal) between the
// node values read_mesh gives (a .gr3's depths, a .2dm's z...); off the mesh, within
// about a triangle's size of it, the value at the nearest point of its boundary, else
// NaN. The mesh is read in its file's CRS, else in `crs_if_none` (CRS text), else, as a
// raster without one, in the query CRS.
class MeshNodeField : public PointField {
 public:
  enum class Values {
    nodes,          // the file's node values (read_mesh's node_values)
    element_sizes,  // each node's mean side length (metres, in the query CRS) over its elements
  };
  // `what` names the option in messages (e.g. "--bathymetry"). Throws Error(input) for a
  // mesh read_mesh cannot read or whose nodes have no values, Error(crs) for a CRS that
  // cannot be used.
  // With `extent` ({xmin, ymin, xmax, ymax} in the query CRS), only the elements within a
  // quarter of its larger side of it are kept (a regional model's grid giving the depths
  // of a bay): none there, NaN everywhere.
  MeshNodeField(const std::string& path, const std::string& what, const CrsInfo& query_crs,
                const std::string& crs_if_none = "", Values values = Values::nodes,
                const std::optional<std::array<double, 4>>& extent = std::nullopt);
  // A triangulation's node values (scattered samples' Delaunay triangles), its points
  // already in the query CRS.
  MeshNodeField(std::vector<Point2> points, std::vector<double> values,
                std::vector<std::array<int, 3>> triangles);
  double sample(const Point2& p) const override;
  // The mean of the node values in the square where it holds at least kMinAveraged nodes
  // (nodes finer than the square, as a raster's two cells across it) and p is on the
  // mesh; else sample(p).
  double mean_over(const Point2& p, double half_width) const override;
  static constexpr int kMinAveraged = 4;
  // The largest node value, each divided by `divisor` at its node when given (a map's
  // scale: element sizes on the ground).
  double max_value(const std::function<double(const Point2&)>& divisor = {}) const;
  std::string kept_text() const override;

 private:
  void index_triangles();       // the grid below, from points_ and triangles_
  std::vector<Point2> points_;  // in the query CRS
  std::vector<double> values_;
  std::vector<std::array<int, 3>> triangles_;
  std::size_t num_read_nodes_ = 0;  // before those far from the extent were left out
  // A grid over the mesh's box: each cell's triangles (whose boxes meet it), as ranges
  // of cell_triangles_.
  double x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_, cell_triangles_;
  // The same grid's nodes, as ranges of cell_nodes_.
  std::vector<int> node_start_, cell_nodes_;
};

// Reads the mesh as MeshNodeField would, for its errors before a long job.
void check_mesh_field(const std::string& path, const std::string& what);

}  // namespace isoquad
