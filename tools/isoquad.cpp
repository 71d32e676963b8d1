// isoquad command-line interface: parses arguments into option structs (cli_args.h) and
// runs the subcommands on the library. Every failure maps to one exit code (see kExitCodes
// below and README.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/versions.h"
#include "cli_args.h"
#include "cli_each.h"
#include "cli_jobs.h"
#include "core/error.h"
#include "core/stage_clock.h"
#include "gis/atomic_output.h"
#include "gis/where_hint.h"

namespace {

using namespace isoquad;
using namespace isoquad::cli;

const char* kExitCodes =
    "Exit codes:\n"
    "  0   success\n"
    "  2   usage: bad command line or option value\n"
    "  3   input: missing, unreadable or invalid input data, empty selection\n"
    "  4   crs: missing or unknown CRS, coordinates outside the CRS's valid range\n"
    "  5   meshing: a meshing stage failed\n"
    "  6   output: output exists (see --overwrite) or cannot be written\n"
    "  70  internal error (a bug: please report it)\n"
    "  130 stopped by Ctrl-C (SIGINT; 143 SIGTERM, 129 SIGHUP): outputs not yet complete\n"
    "      are removed, those of regions already meshed (--each) kept\n";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "isoquad: isotropic all-quadrangle meshes of map polygons (coastlines, lakes, sea "
      "areas) that follow a sizing field and a cross field."};
  app.footer(kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    return std::string("isoquad ") + ISOQUAD_VERSION +
           "\nlibraries: " + isoquad::library_versions_line();
  });

  CommonArgs domain_args;
  CLI::App* domain_cmd = app.add_subcommand(
      "domain",
      "Read, select, project, repair and simplify polygons; write the planar domain (in the "
      "meshing CRS) as a GeoPackage with its open parts (or .fgb, or .geojson in lon/lat) and "
      "print a summary.");
  add_front_end_options(domain_cmd, domain_args);
  add_open_boundary_options(domain_cmd, domain_args.fe);
  domain_cmd->footer(kExitCodes);

  CommonArgs fields_args;
  FieldArgs field_args;
  CLI::App* fields_cmd = app.add_subcommand(
      "fields",
      "Build the background mesh with the sizing field and the cross field, and write them "
      "(.vtu for ParaView: point data size (m) and cross_angle (deg); .gpkg for QGIS: layers "
      "vertices and triangles with size_m and cross_angle_deg, drawn by size).");
  add_front_end_options(fields_cmd, fields_args);
  add_field_options(fields_cmd, field_args);
  add_open_boundary_options(fields_cmd, fields_args.fe);
  fields_cmd->footer(kExitCodes);

  CommonArgs mesh_args;
  mesh_args.many_outputs = true;
  FieldArgs mesh_field_args;
  MeshArgs mesh_extra;
  CLI::App* mesh_cmd = app.add_subcommand(
      "mesh",
      "The main job: an isotropic all-quadrangle mesh of the domain that follows the sizing "
      "and cross fields, with a quality summary; outputs for GIS and ocean models (.gpkg, "
      ".vtu, .vtk, .msh, .gr3, .nc, .2dm, .mesh, .pli, .slf, .14; the quads alone as .geojson "
      "or .fgb), several in one run. Every quad "
      "written is strictly convex and none overlap: a tiling that leaves one otherwise is "
      "retried (up to 6 tilings, each with the sizes halved where the one before failed), "
      "and the run stops without writing when all fail.");
  add_front_end_options(mesh_cmd, mesh_args);
  add_field_options(mesh_cmd, mesh_field_args);
  add_mesh_options(mesh_cmd, mesh_extra);
  add_open_boundary_options(mesh_cmd, mesh_args.fe);
  mesh_cmd->footer(kExitCodes);

  CommonArgs quality_args;
  quality_args.output_optional = true;
  quality_args.input_optional = true;
  FieldArgs quality_field_args;
  QualityArgs quality_extra;
  CLI::App* quality_cmd = app.add_subcommand(
      "quality",
      "Measure a mesh made by another tool (Gmsh, SMS, OceanMesh2D...) or an earlier run "
      "(--mesh: .gpkg, .geojson, .fgb, .gr3, .ll, .14, .2dm, .msh, .mesh, .nc, .slf, .vtu, .vtk) "
      "as `mesh` "
      "measures its "
      "own: angles, regularity, SCHISM's and D-Flow FM's checks, and its sizes and "
      "orientation against the fields that INPUT and the same options give (without INPUT: "
      "the mesh's own outline, in its CRS); the same summary and --report.");
  add_front_end_options(quality_cmd, quality_args);
  add_field_options(quality_cmd, quality_field_args);
  add_quality_options(quality_cmd, quality_extra);
  add_open_boundary_options(quality_cmd, quality_args.fe);
  quality_cmd->footer(kExitCodes);

  try {
    // Parsed from the checked words (CLI11 takes them in reverse order).
    std::vector<std::string> args = checked_arguments(app, argc, argv);
    std::reverse(args.begin(), args.end());
    if (app.get_name().empty()) app.name(argv[0]);  // as parse(argc, argv) names it
    app.parse(args);
    check_option_values(app);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, as every error: with the help of the subcommand it was parsing.
    std::string help = "isoquad --help", what = e.what();
    const CLI::App* parsed = nullptr;
    for (const CLI::App* sub : app.get_subcommands())
      if (sub->parsed()) parsed = sub, help = "isoquad " + sub->get_name() + " --help";
    // Stopped before parsing (checked_arguments): the subcommand named first.
    for (const CLI::App* sub : app.get_subcommands({}))
      if (!parsed && argc > 1 && sub->get_name() == argv[1])
        help = "isoquad " + sub->get_name() + " --help";
    // An option it does not have: the nearest it has, by spelling.
    if (parsed && dynamic_cast<const CLI::ExtrasError*>(&e))
      for (const std::string& extra : parsed->remaining()) {
        if (extra.rfind("--", 0) != 0) continue;
        const std::string name = extra.substr(2, extra.find('=') - 2);
        std::vector<std::string> names;
        for (const CLI::Option* o : parsed->get_options())
          for (const std::string& n : o->get_lnames()) names.push_back(n);
        // Another subcommand's option, or a misspelling.
        std::string others;
        for (const CLI::App* sub : app.get_subcommands({}))
          if (sub != parsed && sub->get_option_no_throw("--" + name))
            others += (others.empty() ? "" : ", ") + sub->get_name();
        const std::vector<std::string> near = nearest_values(name, names, 1);
        what = !others.empty()
                   ? "--" + name + " is an option of " + others + ", not of " + parsed->get_name()
                   : "unknown option --" + name +
                         (near.empty() ? "" : "; did you mean --" + near[0] + "?");
        break;
      }
    // CLI11's wording for an option given twice, or a value of the wrong kind.
    const std::string at_most = ": At Most 1 required but received ";
    if (const std::size_t at = what.find(at_most); at != std::string::npos)
      what = what.substr(0, at) + " is given " + what.substr(at + at_most.size()) +
             " times; give it once";
    const std::string convert = "Could not convert: ";
    if (what.rfind(convert, 0) == 0) {
      const std::string rest = what.substr(convert.size());  // "--jobs = 1.5"
      const std::size_t eq = rest.find(" = ");
      if (eq != std::string::npos) {
        const std::string name = rest.substr(0, eq), value = rest.substr(eq + 3);
        const CLI::Option* o = parsed ? parsed->get_option_no_throw(name) : nullptr;
        const std::string type = o ? o->get_type_name() : "";
        what = name + ": '" + value + "' is not " +
               (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0 ? "a whole number"
                : type.rfind("FLOAT", 0) == 0                           ? "a number"
                                                                        : "a valid value");
      }
    }
    std::cerr << "isoquad: usage: " << what << " (" << help << " lists the options)\n";
    return exit_code(ErrorClass::usage);
  }

  for (const CLI::Option* o : mesh_cmd->get_options()) {
    std::vector<std::string> names;
    for (const std::string& name : o->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : o->get_snames()) names.push_back("-" + name);
    if (names.empty()) continue;                                          // INPUT
    const OptionShape shape{names.front(), o->get_items_expected_max()};  // 0: a flag
    for (const std::string& name : names) mesh_extra.option_shapes[name] = shape;
  }

  // Before any thread starts (the signals' own, the stages' helpers): the heap's pools,
  // then the signals every thread blocks, so that Ctrl-C or a batch system's SIGTERM
  // leaves no temporary file.
  limit_heap_arenas(mesh_cmd->parsed()      ? mesh_extra.jobs
                    : quality_cmd->parsed() ? quality_extra.jobs
                                            : 1);
  isoquad::remove_unfinished_outputs_on_signals();
  // The run's inputs, which no output may replace: INPUT and --mesh noted now, so that an
  // output named as one fails before any work; the other files as they are read.
  const ProtectInputFiles protect_inputs;
  for (const std::string* input : {&domain_args.input, &fields_args.input, &mesh_args.input,
                                   &quality_args.input, &quality_extra.mesh_path})
    note_input_file(*input);
  try {
    if (domain_cmd->parsed()) return run_domain(domain_args);
    if (fields_cmd->parsed()) return run_fields(fields_args, field_args, joined_command_line(argc, argv));
    if (mesh_cmd->parsed() && mesh_extra.skip_existing && mesh_args.overwrite)
      throw Error(ErrorClass::usage, "options",
                  "--skip-existing keeps existing outputs, --overwrite replaces them: give one");
    if (mesh_cmd->parsed() && (!mesh_extra.each.empty() || !mesh_extra.each_clip.empty()))
      return run_mesh_each(mesh_args, mesh_field_args, mesh_extra, joined_command_line(argc, argv));
    if (mesh_cmd->parsed() && mesh_extra.jobs != 1)
      throw Error(ErrorClass::usage, "options",
                  "--jobs meshes the regions of --each at once: give --each");
    if (mesh_cmd->parsed() && !mesh_extra.each_table.empty())
      throw Error(ErrorClass::usage, "options", "--each-table is --each's table: give --each");
    if (mesh_cmd->parsed() && mesh_extra.skip_existing &&
        every_output_exists(mesh_args, mesh_field_args, mesh_extra)) {
      if (mesh_args.quiet) return 0;
      std::cerr << "skipped: every output exists (--skip-existing)\n";
      for (const std::string& w :
           skipped_outputs_warnings(mesh_args, mesh_extra, joined_command_line(argc, argv)))
        std::cerr << "isoquad: warning: " << w << "\n";
      return 0;
    }
    if (mesh_cmd->parsed() && mesh_extra.skip_existing)
      check_not_partly_written(mesh_args, mesh_field_args, mesh_extra);
    if (quality_cmd->parsed() && !quality_extra.each.empty())
      return run_quality_each(quality_args, quality_field_args, quality_extra,
                              joined_command_line(argc, argv));
    if (quality_cmd->parsed() && quality_extra.jobs != 1)
      throw Error(ErrorClass::usage, "options",
                  "--jobs measures the regions of --each at once: give --each");
    if (quality_cmd->parsed() && !quality_extra.each_table.empty())
      throw Error(ErrorClass::usage, "options", "--each-table is --each's table: give --each");
    if (quality_cmd->parsed()) {
      run_quality(quality_args, quality_field_args, quality_extra, joined_command_line(argc, argv));
      return 0;
    }
    if (mesh_cmd->parsed()) {
      run_mesh(mesh_args, mesh_field_args, mesh_extra, joined_command_line(argc, argv));
      return 0;
    }
  } catch (const Error& e) {
    end_progress_line();
    std::cerr << "isoquad: " << e.what() << "\n";
    return exit_code(e.error_class());
  } catch (const std::exception& e) {
    end_progress_line();
    std::cerr << "isoquad: internal error: " << e.what() << "\n";
    return exit_code(ErrorClass::internal);
  }
  return exit_code(ErrorClass::usage);
}
