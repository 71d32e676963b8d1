// The isoquad command line's arguments: the option structs of the subcommands, their
// options registered with CLI11 (with the help texts), and their checks and conversions
// into the library's options.
#pragma once

#include <CLI/CLI.hpp>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/command_record.h"
#include "app/fields_job.h"
#include "app/front_end.h"
#include "app/mesh_job.h"
#include "app/quad_zones.h"
#include "io/write_mesh.h"

namespace isoquad::cli {

// Arguments of every subcommand: the input, its selection, projection and cleaning, and
// the outputs.
struct CommonArgs {
  std::string input;
  std::vector<std::string> outputs;  // -o, repeatable for `mesh`
  std::string output;                // the first
  bool many_outputs = false;         // the subcommand accepts several -o
  bool output_optional = false;      // -o may be left out (`quality`)
  bool input_optional = false;       // INPUT may be left out (`quality`: the mesh's outline)
  std::string bbox;
  std::string domain_kind;  // empty: not given (land)
  double simplify_m = -1.0;
  double min_island_area_m2 = -1.0;
  double min_width_m = -1.0;
  double hairline_m = -1.0;
  std::string report_path;
  bool overwrite = false;
  bool quiet = false;
  FrontEndOptions fe;
  // A region of --each or --each-clip: the option, its attribute and the region's value
  // (empty for the features without one), for the GeoPackage's metadata.
  std::vector<std::pair<std::string, std::string>> region;
};

// Options of the background mesh and the fields (`fields` and `mesh`).
struct FieldArgs {
  SizingParams sizing;
  bool size_auto = false;
  std::string cross = "boundary";
  double cross_angle_deg = std::numeric_limits<double>::quiet_NaN();
  std::string cross_raster;
  double cross_conformal = CrossParams{}.conformal;
  std::string align_path, align_layer;
  double background_factor = 0.25;
  double max_quads = FieldsOptions{}.max_quads;
  std::optional<double> min_depth_m;  // --min-depth
  std::string depth_field;            // --depth-field: samples' values in this attribute
  std::string depth_crs;              // --depth-crs: of depth files without a CRS
  std::string plot_path;
};

// The mesh subcommand's own arguments.
struct MeshArgs {
  MeshOptions mesh;
  // How many values each of the subcommand's options takes, by its names (0: a flag):
  // to compare a recorded command with this one (--skip-existing).
  std::map<std::string, OptionShape> option_shapes;
  std::vector<std::string> output_formats;
  std::string msh_version = "4.1";
  std::string msh_groups = "kind";
  std::string output_crs;
  std::string numbering = "rcm";  // --numbering
  bool schism_split = false;
  bool depth_average = false;  // --depth-average
  ZonesSource zones;           // --zones, --zones-layer, --zones-field
  std::string embed_points;    // --embed-points
  std::string embed_points_name;  // --embed-points-name
  std::string stop_after;  // empty: the whole job
  std::string conform_rule = "lattice";
  std::string init = "front";
  std::string each;            // --each FIELD: a mesh per value of the attribute
  std::string each_clip;       // --each-clip FIELD: a mesh per value over --clip's polygons
  std::string each_table;      // --each-table: the batch's table as CSV
  int jobs = 1;                // --jobs: regions of --each meshed at once
  bool skip_existing = false;  // --skip-existing: nothing to do where every output exists
};

// The quality subcommand's own arguments.
struct QualityArgs {
  std::string mesh_path;  // --mesh
  std::string mesh_crs;   // --mesh-crs
  std::string each;       // --each FIELD: a mesh measured per value of the attribute
  std::string each_table;  // --each-table: the batch's table as CSV
  int jobs = 1;           // --jobs: regions of --each measured at once
};

// Input, selection, projection, cleaning and the outputs every subcommand has.
void add_front_end_options(CLI::App* cmd, CommonArgs& a);
// The mesh to measure (`quality`).
void add_quality_options(CLI::App* cmd, QualityArgs& q);
// Sizing, the cross field and the background mesh (`fields` and `mesh`).
void add_field_options(CLI::App* cmd, FieldArgs& f);
// For `domain` (its summary says how much of the boundary the lines follow) and `mesh`.
void add_open_boundary_options(CLI::App* cmd, FrontEndOptions& fe);
// The tiling, the quads and the mesh outputs (`mesh`).
void add_mesh_options(CLI::App* cmd, MeshArgs& m);

// Before parsing: the arguments as CLI11 should read them, after the program's name.
// `--opt=` (an empty shell variable) becomes `--opt ""`, and `-o=FILE` becomes `-o FILE`,
// so that neither takes the next word (or '=FILE') as its value; an option that takes a
// value followed by another of the subcommand's options (`--report --overwrite`, its
// value forgotten) throws CLI::ValidationError naming both, where CLI11 would take the
// option's name as the value (a report written to a file named --overwrite).
std::vector<std::string> checked_arguments(const CLI::App& app, int argc, char** argv);

// After parsing: throws CLI::ValidationError for an option of the parsed subcommands given
// an empty value (an unset shell variable would otherwise leave it out unseen) or, taking
// a number, a value that is not a finite decimal number (nan, inf, hex), which range
// checks let through.
void check_option_values(const CLI::App& app);
// The front end's options from the arguments (the first output, the bbox, the domain's
// kind, the cleaning); Error(usage) for arguments that do not fit together.
void finish_front_end_args(CommonArgs& a);
// The fields' options from the arguments; Error(usage) for arguments that do not fit
// together.
FieldsOptions fields_options(const CommonArgs& a, const FieldArgs& f);
// The depth rasters can be read, and the options that need depths have them; a mesh
// among them without a CRS of its own is in --src-crs, when given.
void finish_depth_options(const CommonArgs& a, FieldArgs& f);
// The mesh outputs with their formats (--output-format, once or once per -o).
std::vector<MeshOutput> mesh_outputs(const CommonArgs& a, const MeshArgs& m);
// The mesh job's options from the arguments (the fields', the tiling's choices named on
// the command line); Error(usage) for --embed without --align.
MeshOptions mesh_options(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m);
// The writers' options (--msh-version, --msh-groups, --output-crs, --schism-split).
MeshWriteOptions mesh_write_options(const MeshArgs& m);
// --skip-existing: every file the run would write exists.
bool every_output_exists(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m);

// With --skip-existing: Error(usage) naming what exists and what is missing when some of
// the outputs (with the files written beside them, --report and --plot) exist and
// others do not.
void check_not_partly_written(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m);

}  // namespace isoquad::cli
