// D-Flow FM polyline file (.pli, a Tekal block) of one open boundary segment: its name
// (the file's stem, which D-Flow FM prefixes to the support points' names in .bc forcing
// files: NAME_0001, NAME_0002...), the line "points 2", then every boundary node of the
// segment in order (domain on the left); a closed segment repeats its first node.
#include <cstdio>
#include <filesystem>

#include "io/mesh_formats.h"
#include "io/output_file.h"

namespace isoquad {

void write_pli_file(const MeshView& v, const BoundarySegment& segment, const std::string& path,
                    const std::string& what) {
  std::vector<int> nodes = segment.nodes;
  if (segment.closed && !nodes.empty()) nodes.push_back(nodes.front());
  OutputFile f(path, what);
  const char* xy = v.geographic ? "    %.10f    %.10f\n" : "    %.6f    %.6f\n";
  std::fprintf(f.get(), "%s\n%zu    2\n", std::filesystem::path(what).stem().string().c_str(),
               nodes.size());
  for (int n : nodes) std::fprintf(f.get(), xy, v.points[n].x, v.points[n].y);
  f.close();
}

}  // namespace isoquad
