// What the mesh job writes (app/mesh_outputs.h): every output of a run or none.
#include "app/mesh_outputs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "core/error.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

namespace {

const MeshResult& corsica_mesh() {
  static const MeshResult r = [] {
    MeshOptions o;
    o.fields.front.read.path = sample("corsica.shp");
    o.fields.sizing.hmax_m = 8000;
    return build_mesh(o);
  }();
  return r;
}

std::set<std::string> entries(const TempDir& dir) {
  const auto e = dir.entries();
  return {e.begin(), e.end()};
}

}  // namespace

TEST(MeshJobOutputs, WritesEveryMeshThePlotAndTheReport) {
  const MeshResult& r = corsica_mesh();
  ASSERT_TRUE(r.has_quads);
  TempDir dir;
  MeshJobOutputs o;
  o.meshes = {{dir.file("m.gpkg"), "", false}, {dir.file("hgrid.gr3"), "", false}};
  o.plot_path = dir.file("m.png");
  o.report_path = dir.file("m.json");
  o.command_line = "isoquad mesh corsica.shp";
  const MeshJobWritten w = write_mesh_job_outputs(r, o);
  EXPECT_EQ(entries(dir),
            (std::set<std::string>{"m.gpkg", "hgrid.gr3", "hgrid.ll", "m.png", "m.json"}));
  // A land domain: every boundary edge is land, as many as the mesh has.
  EXPECT_EQ(w.num_open_edges, 0u);
  EXPECT_EQ(w.num_land_edges, boundary_edges(r.quads).size());
  EXPECT_FALSE(w.depths);  // no bathymetry
  EXPECT_NE(
      read_file(dir.file("m.json")).find("\"num_quads\": " + std::to_string(r.quality.num_quads)),
      std::string::npos);
  const auto items = quality_items(r.quality);
  const auto quads = std::find_if(items.begin(), items.end(),
                                  [](const auto& kv) { return kv.first == "num_quads"; });
  ASSERT_NE(quads, items.end());
  EXPECT_EQ(quads->second, std::to_string(r.quality.num_quads));
  // The writing is a stage of its own, the report's last.
  EXPECT_EQ(w.output_time.stage, "output");
  EXPECT_GT(w.output_time.seconds, 0.0);
  EXPECT_GT(w.output_time.peak_mb, 0.0);
  const std::string json = read_file(dir.file("m.json"));
  const std::size_t last = json.rfind("\"stage\": ");
  ASSERT_NE(last, std::string::npos);
  EXPECT_EQ(json.substr(last, 17), "\"stage\": \"output\"");
}

TEST(MeshJobOutputs, AnOutputThatCannotBeWrittenLeavesNoneOfThem) {
  const MeshResult& r = corsica_mesh();
  TempDir dir;
  write_file(dir.file("m.json"), "old");
  std::filesystem::create_directory(dir.file("gone"));
  MeshJobOutputs o;
  o.meshes = {{dir.file("m.gpkg"), "", false}, {dir.file("gone/m.msh"), "", false}};
  o.report_path = dir.file("m.json");
  o.overwrite = true;
  // Checked, then its folder removed before the writing (as another process might).
  check_mesh_outputs(o.meshes, o.write);
  std::filesystem::remove(dir.file("gone"));
  EXPECT_THROW(write_mesh_job_outputs(r, o), Error);
  EXPECT_EQ(entries(dir), (std::set<std::string>{"m.json"}));
  EXPECT_EQ(read_file(dir.file("m.json")), "old");
}
