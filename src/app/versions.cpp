#include "app/versions.h"

#include <CGAL/version.h>
#include <GeographicLib/Config.h>
#include <gdal.h>
#include <geos_c.h>
#include <netcdf.h>
#include <ogr_srs_api.h>
#include <sleef.h>

#include <Eigen/Core>
#include <cctype>

namespace isoquad {

namespace {

// The leading "major.minor.patch" of a version text ("3.11.1-CAPI-1.17.1", "4.9.0 of
// Jan 23 2023 ...").
std::string leading_version(const std::string& text) {
  std::size_t n = 0;
  while (n < text.size() && (std::isdigit(static_cast<unsigned char>(text[n])) || text[n] == '.'))
    ++n;
  return n ? text.substr(0, n) : text;
}

// PROJ's, as GDAL (through which isoquad uses it) reports it.
std::string proj_version() {
  int major = 0, minor = 0, patch = 0;
  OSRGetPROJVersion(&major, &minor, &patch);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> library_versions() {
  return {
      {"CGAL", CGAL_VERSION_STR},
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION)},
      {"GDAL", GDALVersionInfo("RELEASE_NAME")},
      {"GEOS", leading_version(GEOSversion())},
      {"PROJ", proj_version()},
      {"GeographicLib", GEOGRAPHICLIB_VERSION_STRING},
      {"netCDF", leading_version(nc_inq_libvers())},
      {"SLEEF", std::to_string(SLEEF_VERSION_MAJOR) + "." + std::to_string(SLEEF_VERSION_MINOR) +
                    "." + std::to_string(SLEEF_VERSION_PATCHLEVEL)},
  };
}

std::string library_versions_line() {
  std::string line;
  for (const auto& [name, version] : library_versions())
    line += (line.empty() ? "" : ", ") + name + " " + version;
  return line;
}

}  // namespace isoquad
