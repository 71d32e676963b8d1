// The versions of the libraries whose code decides the output (the meshes' last bits
// move with PROJ's, GEOS's, CGAL's...), for --version, the reports and the GeoPackage's
// metadata: a golden file that changes after an upgrade says which library moved.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace isoquad {

// (name, version) in a fixed order: the ones linked at run time as the loaded library
// reports them (GDAL, GEOS, PROJ, netCDF), the header-only ones as compiled in (CGAL,
// Eigen), the others as compiled against (GeographicLib, SLEEF).
std::vector<std::pair<std::string, std::string>> library_versions();

// "CGAL 5.5.1, Eigen 3.4.0, ..." on one line.
std::string library_versions_line();

}  // namespace isoquad
