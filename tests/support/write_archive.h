// Archives for the tests of inputs read as downloaded (.zip, .gz), written with GDAL's
// own zip and gzip writers.
#pragma once

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "support/test_support.h"

namespace isoquad::test {

// Writes a zip at `path` holding each (member name, bytes) in order; returns `path`.
inline std::string write_zip(const std::string& path,
                             const std::vector<std::pair<std::string, std::string>>& members) {
  void* zip = CPLCreateZip(path.c_str(), nullptr);
  EXPECT_NE(zip, nullptr) << path;
  for (const auto& [name, bytes] : members) {
    EXPECT_EQ(CPLCreateFileInZip(zip, name.c_str(), nullptr), CE_None) << name;
    EXPECT_EQ(CPLWriteFileInZip(zip, bytes.data(), static_cast<int>(bytes.size())), CE_None);
    EXPECT_EQ(CPLCloseFileInZip(zip), CE_None);
  }
  EXPECT_EQ(CPLCloseZip(zip), CE_None);
  return path;
}

// The files of a shapefile (`stem` + .shp, .shx, .dbf, .prj, .cpg where they exist) as
// archive members named `folder` + their file names.
inline std::vector<std::pair<std::string, std::string>> shapefile_members(
    const std::string& stem, const std::string& folder) {
  std::vector<std::pair<std::string, std::string>> members;
  const std::string name = stem.substr(stem.find_last_of('/') + 1);
  for (const char* ext : {".shp", ".shx", ".dbf", ".prj", ".cpg"})
    if (std::ifstream(stem + ext)) members.emplace_back(folder + name + ext, read_file(stem + ext));
  return members;
}

// Writes `bytes` gzipped at `path`; returns `path`.
inline std::string write_gzip(const std::string& path, const std::string& bytes) {
  VSILFILE* f = VSIFOpenL(("/vsigzip/" + path).c_str(), "wb");
  EXPECT_NE(f, nullptr) << path;
  EXPECT_EQ(VSIFWriteL(bytes.data(), 1, bytes.size(), f), bytes.size());
  VSIFCloseL(f);
  return path;
}

}  // namespace isoquad::test
