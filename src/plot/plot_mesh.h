// The paper's pictures of a quad mesh (sections 2 and 3): the mesh with irregular
// vertices (red: degree excess, blue: deficit), quads coloured by size conformance
// (white to blue smaller, white to red larger than h) and by orientation deviation
// (white to grey, grey = 45 degrees), and the distributions of angles, size ratio and
// orientation deviation.
#pragma once

#include <string>
#include <vector>

#include "quad/quad_mesh.h"
#include "quad/quad_quality.h"

namespace isoquad {

struct PlotMeshParams {
  std::string path;
  int panel_px = 900;  // width of each map panel
  bool overwrite = false;
  // Lines drawn over the map panels, in the mesh's coordinates: the --align lines in
  // dark green, and over them --embed's paths of edges in magenta.
  std::vector<std::vector<Point2>> lines;
  std::vector<std::vector<Point2>> embedded;
};

void plot_mesh(const QuadMesh& mesh, const QuadMetrics& metrics, const QualitySummary& summary,
               const PlotMeshParams& params);

}  // namespace isoquad
