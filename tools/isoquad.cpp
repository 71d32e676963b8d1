// isoquad command-line interface: parses arguments into option structs (cli_args.h) and
// runs the subcommands on the library. Every failure maps to one exit code (see kExitCodes
// below and README.md).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

#include "app/each_job.h"
#include "app/fields_job.h"
#include "app/front_end.h"
#include "app/mesh_job.h"
#include "app/mesh_outputs.h"
#include "app/quality_job.h"
#include "app/quality_report.h"
#include "app/summary.h"
#include "app/versions.h"
#include "cli_args.h"
#include "core/error.h"
#include "core/stage_clock.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/gdal_env.h"
#include "gis/raster_domain.h"
#include "gis/read_mesh.h"
#include "gis/read_polygons.h"
#include "gis/read_size_features.h"
#include "gis/where_hint.h"
#include "gis/write_domain.h"
#include "io/mesh_boundary.h"
#include "io/write_fields.h"
#include "io/write_mesh.h"
#include "plot/plot_fields.h"
#include "plot/plot_mesh.h"

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

// A progress line is on the terminal without its newline: a message must clear it first.
std::atomic<bool> progress_line_open{false};

// Clears an unfinished progress line, so that an error or warning starts its own line.
void end_progress_line() {
  if (progress_line_open.exchange(false)) std::fprintf(stderr, "\r\033[K");
}

// Renders progress on stderr, throttled, only when stderr is a terminal.
ProgressCallback make_progress(bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return nullptr;
  // At most ten lines a second for one stage; a new stage shows at once (a long one that
  // starts right after a short one would otherwise show under the short one's name).
  struct Shown {
    std::chrono::steady_clock::time_point at;
    std::string stage;
  };
  auto last = std::make_shared<Shown>();
  return [last](const std::string& stage, double f) {
    const auto now = std::chrono::steady_clock::now();
    if (f < 1.0 && stage == last->stage && now - last->at < std::chrono::milliseconds(100))
      return true;
    last->at = now;
    last->stage = stage;
    // \033[K clears what a longer line before left on the right.
    std::fprintf(stderr, "\r%-12s %3d%%\033[K%s", stage.c_str(), static_cast<int>(f * 100 + 0.5),
                 f >= 1.0 ? "\n" : "");
    std::fflush(stderr);
    progress_line_open = f < 1.0;
    return true;
  };
}

// --report - (kStdoutPath): the JSON goes to stdout (which nothing else uses), after every
// file is in place; no file is checked or written for it.
void check_report_path(const CommonArgs& a) {
  if (!a.report_path.empty() && a.report_path != kStdoutPath)
    check_output_path(a.report_path, a.overwrite);
}

// Adds the report to the outputs written together, unless it goes to stdout.
// The report written beside the other outputs, all moved into place together, then
// the report on stdout when asked (--report -), once every output is written.
void commit_with_report(const CommonArgs& a, OutputSet& set, const std::string& json) {
  if (!a.report_path.empty() && a.report_path != kStdoutPath)
    write_text_file(set.add(a.report_path, a.overwrite), json, true);
  set.commit_all();
  if (a.report_path == kStdoutPath) std::cout << json << std::flush;
}

int run_domain(CommonArgs& a) {
  finish_front_end_args(a);
  // Fail before any work when an output cannot be written.
  check_output_path(a.output, a.overwrite);
  check_report_path(a);
  if (!is_domain_output(a.output))
    throw Error(ErrorClass::usage, "options",
                "'" + a.output +
                    "': the domain is written as a GeoPackage (.gpkg), a FlatGeobuf (.fgb) or a "
                    "GeoJSON in longitudes and latitudes (.geojson, .json)");

  // With --size, cleaned as `mesh --size` cleans (at the ground's sizes over a large
  // domain); without it, the cleaning's options alone.
  if (a.fe.target_size_m > 0) {
    SizingParams sizing;
    sizing.automatic = false;
    sizing.constant_m = a.fe.target_size_m;
    clean_at_sizes(a.fe, sizing);
  }
  const auto t0 = std::chrono::steady_clock::now();
  FrontEndResult r = build_planar_domain(a.fe, Progress(make_progress(a.quiet)));
  // The domain and the report are moved into place together, when both are complete.
  OutputSet set;
  WriteDomainParams wp;
  wp.path = set.add(a.output, a.overwrite);
  wp.final_path = a.output;
  wp.overwrite = true;
  wp.open_parts = &r.open_boundary_parts;
  write_domain(r.domain, wp);
  const std::string report = domain_summary_json(r.summary);
  commit_with_report(a, set, report);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    std::cerr << format_domain_summary(r.summary);
    std::cerr << "output:       " << a.output << " (layer 'domain'"
              << (r.open_boundary_parts.empty() ||
                          lower_case(std::filesystem::path(a.output).extension().string()) !=
                              ".gpkg"
                      ? ""
                      : ", and 'open_boundary': " + std::to_string(r.open_boundary_parts.size()) +
                            " line(s)")
              << ")\n";
    std::fprintf(stderr, "time:         %.3f s\n", seconds);
    for (const std::string& w : r.summary.warnings) std::cerr << "isoquad: warning: " << w << "\n";
  }
  return 0;
}

int run_fields(CommonArgs& a, FieldArgs& f, const std::string& command_line) {
  finish_front_end_args(a);
  check_output_path(a.output, a.overwrite);
  if (!f.plot_path.empty()) check_output_path(f.plot_path, a.overwrite);
  check_report_path(a);
  const std::string ext = std::filesystem::path(a.output).extension().string();
  if (ext != ".vtu" && ext != ".gpkg")
    throw Error(ErrorClass::usage, "options", "'" + a.output + "': the fields are written as .vtu or .gpkg");
  finish_depth_options(a, f);
  const FieldsOptions options = fields_options(a, f);
  const auto t0 = std::chrono::steady_clock::now();
  FieldsResult r = build_fields(options, Progress(make_progress(a.quiet)));
  // The fields, the plot and the report are moved into place together, when all are
  // complete. Writing the fields and the plot is the stage "output".
  StageClock clock(r.times);
  OutputSet set;
  const SizingField ground = ground_size_field(r);  // the sizes as the options gave them
  write_fields(r.mesh, ground, r.cross, r.front.domain.crs_wkt, set.add(a.output, a.overwrite),
               true);
  if (!f.plot_path.empty()) {
    PlotFieldsParams pp;
    pp.path = set.add(f.plot_path, a.overwrite);
    pp.overwrite = true;
    plot_fields(r.mesh, ground, r.cross, r.singularities, pp);
  }
  clock.lap("output");
  const std::string report = fields_report_json(r, command_line);
  commit_with_report(a, set, report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    std::cerr << format_domain_summary(r.front.summary) << format_fields_summary(r);
    std::cerr << "output:       " << a.output << (f.plot_path.empty() ? "" : ", " + f.plot_path)
              << "\n";
    std::fprintf(stderr, "time:         %.3f s\n", seconds);
    for (const std::string& w : r.front.summary.warnings) std::cerr << "isoquad: warning: " << w << "\n";
  }
  return 0;
}

// The command line as the outputs record it (a GeoPackage's metadata, a netCDF's history,
// the report): the program as `isoquad`, each argument quoted for a POSIX shell where it
// needs to be, and without the options that change no output (--jobs, --overwrite,
// --skip-existing, -q, --each-table), so that a batch on one thread or two, resumed, or
// run again with --overwrite writes the same bytes.
std::string joined_command_line(int argc, char** argv) {
  auto quoted = [](const std::string& arg) {
    const bool plain = !arg.empty() && arg.find_first_not_of(
                                           "abcdefghijklmnopqrstuvwxyz"
                                           "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                           "0123456789-_./,:=+@%") == std::string::npos;
    if (plain) return arg;
    std::string q = "'";
    for (char c : arg) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  std::string s = "isoquad";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--overwrite" || arg == "--skip-existing" || arg == "-q" || arg == "--quiet" ||
        arg.rfind("--jobs=", 0) == 0 || arg.rfind("--each-table=", 0) == 0)
      continue;
    if (arg == "--jobs" || arg == "--each-table") {
      ++i;  // and its value
      continue;
    }
    s += " " + quoted(arg);
  }
  return s;
}

// The mesh job; with --each, one region's (printing into `console`).
RegionOutcome run_mesh(CommonArgs& a, FieldArgs& f, MeshArgs& m, const std::string& command_line,
                       const Console& console = Console()) {
  const bool tiling_only = !m.stop_after.empty();
  if (tiling_only && !a.outputs.empty())
    throw Error(ErrorClass::usage, "options",
                "--stop-after stops before the quads and writes no mesh: leave out -o (the "
                "tiling goes to --plot and --report)");
  if (tiling_only) a.output_optional = true;
  finish_front_end_args(a);
  const std::vector<MeshOutput> outputs = mesh_outputs(a, m);
  const MeshWriteOptions write_options = mesh_write_options(m);
  if (!tiling_only) check_mesh_outputs(outputs, write_options);
  const bool has_open_boundary =
      !a.fe.open_boundary_path.empty() ||
      (a.fe.kind != DomainKind::land && (!a.bbox.empty() || !a.fe.clip_path.empty())) ||
      a.fe.read.zmin || a.fe.read.zmax;
  for (const MeshOutput& o : outputs)
    if (!tiling_only && !has_open_boundary && mesh_output_format(o) == MeshFormat::pli)
      throw Error(ErrorClass::usage, "options",
                  "'" + o.path +
                      "': a .pli holds the open boundary, and this domain has none: give "
                      "--open-boundary FILE, or --domain water (or sea) with --bbox or --clip");
  // --bathymetry alone gives the depths of the outputs; with a wavelength, slope or time
  // step rule, or a --size-expr in d, it also sets the sizing.
  finish_depth_options(a, f);
  const std::vector<DepthRaster> bathymetry = f.sizing.bathymetry;
  if (m.depth_average && bathymetry.empty())
    throw Error(ErrorClass::usage, "options",
                "--depth-average needs depths: --bathymetry or --elevation");
  // The zones' file is read before the meshing, so that a bad one stops the run early.
  if (m.zones.given())
    read_size_features(m.zones.path, m.zones.layer, m.zones.field, "--zones", "",
                       FeatureValue::zone);
  if (!sizing_reads_depths(f.sizing)) f.sizing.bathymetry.clear();
  if (!f.plot_path.empty()) check_output_path(f.plot_path, a.overwrite);
  check_report_path(a);
  if (tiling_only && f.plot_path.empty() && a.report_path.empty())
    throw Error(ErrorClass::usage, "options", "--stop-after needs --plot or --report to show the tiling");
  const MeshOptions options = mesh_options(a, f, m);
  const auto t0 = std::chrono::steady_clock::now();
  // The outputs (depths, files, plot) take the last 5%: seconds on large meshes.
  const Progress progress(make_progress(a.quiet || !console.progress));
  MeshResult r = build_mesh(options, progress.slice(0.0, 0.95));
  MeshJobOutputs job;
  job.meshes = outputs;
  job.metadata = a.region;
  job.write = write_options;
  job.bathymetry = bathymetry;
  job.min_depth_m = f.min_depth_m;
  job.depth_average = m.depth_average;
  job.zones = m.zones;
  job.courant = f.sizing.courant;
  job.time_step_s = f.sizing.time_step_s;
  job.plot_path = f.plot_path;
  job.report_path = a.report_path;
  job.overwrite = a.overwrite;
  job.command_line = command_line;
  progress.report("write", 0.95);
  const MeshJobWritten written = write_mesh_job_outputs(r, job);
  r.fields.times.push_back(written.output_time);  // for the summary's times
  progress.report("written", 1.0);
  if (a.report_path == kStdoutPath) std::cout << written.report << std::flush;
  RegionOutcome outcome;
  outcome.quality = r.quality;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    for (const std::string& w :
         mesh_job_warnings(r, job, written, options.smooth.max_orthogonality))
      console.err << "isoquad: warning: " << w << "\n";
    console.out << format_domain_summary(r.fields.front.summary) << format_fields_summary(r.fields)
                << format_mesh_summary(r) << format_written_summary(r, job, written);
    if (!f.plot_path.empty()) console.out << "plot:         " << f.plot_path << "\n";
    console.out << printf_string("time:         %.3f s, peak memory %.0f MB\n", outcome.seconds,
                                 process_peak_mb());
    for (const std::string& w : r.fields.front.summary.warnings)
      console.err << "isoquad: warning: " << w << "\n";
  }
  return outcome;
}

// A mesh from a file measured against the domain's fields; -o and --plot as the mesh
// job's, for a mesh of quads alone.
RegionOutcome run_quality(CommonArgs& a, FieldArgs& f, const QualityArgs& q,
                          const std::string& command_line, const Console& console = Console()) {
  finish_front_end_args(a);
  std::vector<MeshOutput> outputs;
  for (const std::string& o : a.outputs) {
    const std::string ext = lower_case(std::filesystem::path(o).extension().string());
    if (ext != ".gpkg" && ext != ".vtu" && ext != ".geojson" && ext != ".fgb")
      throw Error(ErrorClass::usage, "options",
                  "'" + o + "': the measured quads are written as .gpkg, .vtu, .geojson or .fgb");
    outputs.push_back({o, "", a.overwrite});
  }
  if (!outputs.empty()) check_mesh_outputs(outputs, MeshWriteOptions());
  if (!f.plot_path.empty()) check_output_path(f.plot_path, a.overwrite);
  check_report_path(a);
  mesh_file_format(q.mesh_path);  // a format it reads, before any work
  if (a.input.empty()) {
    // The domain is the mesh's outline: nothing to select from, and its CRS is the mesh's.
    const std::pair<bool, const char*> selections[] = {{!a.fe.read.layer.empty(), "--layer"},
                                                       {!a.fe.read.where.empty(), "--where"},
                                                       {!a.bbox.empty(), "--bbox"},
                                                       {!a.fe.read.bbox_crs.empty(), "--bbox-crs"},
                                                       {!a.fe.clip_path.empty(), "--clip"},
                                                       {!a.domain_kind.empty(), "--domain"},
                                                       {!a.fe.read.src_crs.empty(), "--src-crs"}};
    for (const auto& [given, option] : selections)
      if (given)
        throw Error(ErrorClass::usage, "options",
                    std::string(option) +
                        " selects from INPUT: without INPUT the domain is the mesh's own outline "
                        "(its CRS: --mesh-crs)");
  }
  finish_depth_options(a, f);
  if (!f.sizing.bathymetry.empty() && !sizing_reads_depths(f.sizing))
    throw Error(ErrorClass::usage, "options",
                "quality reads depths for the sizes alone: --bathymetry or --elevation needs "
                "--wavelength-period, --slope-factor, --time-step or a --size-expr in d, as the "
                "mesh was made with");
  QualityJobOptions options;
  options.fields = fields_options(a, f);
  options.mesh_path = q.mesh_path;
  options.mesh_crs = q.mesh_crs;
  const auto t0 = std::chrono::steady_clock::now();
  const Progress progress(make_progress(a.quiet || !console.progress));
  const QualityJobResult r = measure_mesh_file(options, progress);
  const bool quads_only = r.num_triangles == 0 && !r.quads.quads.empty();
  if ((!outputs.empty() || !f.plot_path.empty()) && !quads_only)
    throw Error(ErrorClass::usage, "options",
                "'" + q.mesh_path + "' has " + std::to_string(r.num_triangles) +
                    " triangles: -o and --plot show meshes of quadrangles alone");
  OutputSet set;
  if (!outputs.empty()) {
    MeshOutputData data;
    data.mesh = &r.quads;
    data.metrics = &r.metrics;
    data.crs_wkt = r.fields.front.domain.crs_wkt;
    try {
      data.boundary = boundary_of_domain(r.quads, r.fields.front);
    } catch (const Error& e) {
      throw Error(ErrorClass::input, "quality",
                  "'" + q.mesh_path + "': its boundary is not a set of simple loops (" +
                      e.message() + "): -o cannot write it");
    }
    data.command_line = command_line;
    data.libraries = library_versions_line();
    data.quality = quality_items(r.quality);
    write_mesh_outputs(data, outputs, MeshWriteOptions(), set);
  }
  if (!f.plot_path.empty()) {
    PlotMeshParams pp;
    pp.path = set.add(f.plot_path, a.overwrite);
    pp.overwrite = true;
    plot_mesh(r.quads, r.metrics, r.quality, pp);
  }
  const std::string report = quality_job_report_json(r, command_line);
  commit_with_report(a, set, report);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    console.out << format_domain_summary(r.fields.front.summary) << format_fields_summary(r.fields)
                << format_quality_job_summary(r);
    for (const std::string& o : a.outputs) console.out << "output:       " << o << "\n";
    if (!f.plot_path.empty()) console.out << "plot:         " << f.plot_path << "\n";
    console.out << printf_string("time:         %.3f s, peak memory %.0f MB\n", seconds,
                                 process_peak_mb());
    for (const std::string& w : r.fields.front.summary.warnings)
      console.err << "isoquad: warning: " << w << "\n";
    for (const std::string& w : r.warnings) console.err << "isoquad: warning: " << w << "\n";
  }
  RegionOutcome outcome;
  outcome.quality = r.quality;
  outcome.seconds = seconds;
  return outcome;
}

// A region of --each FIELD: the value's features (and --where's) selected, {} in -o,
// --report and --plot replaced by the value made safe for a file name.
struct EachRegion {
  CommonArgs a;
  FieldArgs f;
  std::string value, name, filter;
  std::string id_filter;  // the region's features by their ids (SelectionValue::id_filter)
  bool null = false;      // the features without a value (value "NULL")
  std::size_t index = 0;  // its place among the regions
  bool skip = false;      // mesh --skip-existing, and every output exists
};

// A region per selected value: {} in the paths replaced by its file name.
std::vector<EachRegion> regions_of(const CommonArgs& a, const FieldArgs& f,
                                   const std::string& field,
                                   const std::vector<SelectionValue>& selected) {
  std::vector<std::string> values;
  // Text that is not UTF-8 (a .dbf without its .cpg) read as Windows-1252, for the
  // console, the table, the reports and the file names.
  for (const SelectionValue& v : selected) values.push_back(utf8_or_cp1252(v.text));
  // The features without a value: their file name that of an empty value, "_".
  const std::vector<std::string> names = each_file_names(field, values);
  std::vector<EachRegion> regions;
  for (std::size_t k = 0; k < selected.size(); ++k) {
    EachRegion r{a,
                 f,
                 selected[k].null ? "NULL" : values[k],
                 names[k],
                 selected[k].filter,
                 selected[k].id_filter,
                 selected[k].null};
    r.a.fe.align_optional = true;  // one file of --align lines for all the regions
    r.a.region = {{"each_field", field}, {"each_value", selected[k].null ? "" : values[k]}};
    r.index = k;
    for (std::string& o : r.a.outputs) o = fill_each_mark(o, names[k]);
    r.a.report_path = fill_each_mark(r.a.report_path, names[k]);
    r.f.plot_path = fill_each_mark(r.f.plot_path, names[k]);
    regions.push_back(std::move(r));
  }
  return regions;
}

// --each-clip: a region per value of `field` over the polygons of --clip (and
// --clip-where's), each the area that value picks.
std::vector<EachRegion> each_clip_regions(const CommonArgs& a, const FieldArgs& f,
                                          const CommonArgs& base, const std::string& field) {
  if (base.fe.clip_path.empty())
    throw Error(ErrorClass::usage, "options",
                "--each-clip makes a mesh per polygon of --clip: give --clip");
  ReadParams clip;
  clip.path = base.fe.clip_path;
  clip.layer = base.fe.clip_layer;
  clip.where = base.fe.clip_where;
  std::vector<SelectionValue> selected;
  try {
    selected = selection_values(clip, field);
  } catch (const Error& e) {
    throw read_error_of_option(e, "--clip");
  }
  if (selected.empty())
    throw Error(ErrorClass::input, "read",
                "--clip '" + clip.path + "': no selected feature has a value of '" + field + "'");
  std::vector<EachRegion> regions = regions_of(a, f, field, selected);
  for (EachRegion& r : regions)
    r.a.fe.clip_where =
        a.fe.clip_where.empty() ? r.id_filter : "(" + a.fe.clip_where + ") AND " + r.id_filter;
  return regions;
}

// The regions of --each `field` over the selected features, or with `over_clip`
// (--each-clip) over the polygons of --clip; Error(usage) for a path without {},
// Error(input) when no feature has a value.
std::vector<EachRegion> each_regions(const CommonArgs& a, const FieldArgs& f,
                                     const std::string& field, bool over_clip = false) {
  for (const std::string& o : a.outputs)
    if (!has_each_mark(o))
      throw Error(ErrorClass::usage, "options",
                  "with --each or --each-clip, every -o needs {} for the value (e.g. -o "
                  "out/{}.gpkg): '" +
                      o + "' has none");
  if ((!a.report_path.empty() && !has_each_mark(a.report_path)) ||
      (!f.plot_path.empty() && !has_each_mark(f.plot_path)))
    throw Error(ErrorClass::usage, "options",
                "with --each or --each-clip, --report and --plot need {} for the value");
  CommonArgs base = a;
  finish_front_end_args(base);
  if (over_clip) return each_clip_regions(a, f, base, field);
  if (is_mesh_file(base.fe.read.path))
    throw Error(ErrorClass::usage, "options",
                "'" + base.fe.read.path +
                    "' is a mesh, whose outline is the domain: --each selects from a vector "
                    "file's features");
  if (is_raster_input(base.fe.read.path))
    throw Error(ErrorClass::usage, "options",
                "'" + base.fe.read.path +
                    "' is a raster, whose cells in [--zmin, --zmax] are the domain: --each "
                    "selects from a vector file's features");
  read_clip(base.fe, base.fe.read);  // the values of the features that reach the area
  std::string unmatched;
  const std::vector<SelectionValue> selected =
      selection_values(base.fe.read, field, a.quiet ? nullptr : &unmatched);
  if (!unmatched.empty()) std::cerr << "isoquad: warning: " << unmatched << "\n";
  if (selected.empty())
    throw Error(ErrorClass::input, "read",
                "'" + a.input + "': no selected feature has a value of '" + field + "'");
  std::vector<EachRegion> regions = regions_of(a, f, field, selected);
  for (EachRegion& r : regions) {
    r.a.fe.read.where =
        a.fe.read.where.empty() ? r.id_filter : "(" + a.fe.read.where + ") AND " + r.id_filter;
    r.a.fe.read.hint_unmatched_values = false;
  }
  return regions;
}

// --each-table's file and, for a .csv, its .csvt (each_csv_types_path), checked before
// any meshing.
void check_each_table(const std::string& path, bool overwrite) {
  if (path.empty()) return;
  if (path == "-")
    throw Error(ErrorClass::usage, "options",
                "--each-table -: the table is a CSV file (the console shows it at the end)");
  check_output_path(path, overwrite);
  const std::string types = each_csv_types_path(path);
  if (!types.empty()) check_output_path(types, overwrite);
}

// Every file the regions write (each region's outputs with the files beside them, its
// report and plot) and the batch's table: Error(usage) naming both when two regions, or a
// region and the table, would write the same file (values 'Malta' and 'Malta_1' with
// -o {}.gpkg -o {}_1.gpkg), before any meshing. A .pli of several open segments is
// written as NAME_1.pli, NAME_2.pli...: those names are taken too.
void check_regions_write_apart(const std::vector<EachRegion>& regions,
                               const std::vector<std::vector<MeshOutput>>& outputs,
                               const std::string& field, const std::string& table_path) {
  namespace fs = std::filesystem;
  auto key = [](const std::string& path) { return output_path_key(path); };
  std::map<std::string, std::string> owner;                    // a file's key -> who writes it
  std::vector<std::pair<std::string, std::string>> pli_stems;  // "dir/stem_", who
  auto take = [&](const std::string& path, const std::string& who) {
    const auto [it, added] = owner.emplace(key(path), who);
    if (!added && it->second != who)
      throw Error(ErrorClass::usage, "options",
                  "'" + path + "' would be written by " + it->second + " and by " + who +
                      ": make the -o, --report and --plot templates give each region its "
                      "own files");
  };
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const std::string who = "the region " + field + " = " + regions[k].value;
    for (const MeshOutput& o : outputs[k]) {
      for (const std::string& f : mesh_output_files(o)) take(f, who);
      if (mesh_output_format(o) == MeshFormat::pli) {
        const fs::path p = key(o.path);
        pli_stems.emplace_back((p.parent_path() / p.stem()).string() + "_", who);
      }
    }
    if (!regions[k].a.report_path.empty() && regions[k].a.report_path != "-")
      take(regions[k].a.report_path, who);
    if (!regions[k].f.plot_path.empty()) take(regions[k].f.plot_path, who);
  }
  if (!table_path.empty()) {
    take(table_path, "--each-table");
    const std::string types = each_csv_types_path(table_path);
    if (!types.empty()) take(types, "--each-table");
  }
  for (const auto& [stem, who] : pli_stems)
    for (auto it = owner.lower_bound(stem); it != owner.end() && it->first.rfind(stem, 0) == 0;
         ++it) {
      const std::string number = it->first.substr(stem.size());
      const std::size_t digits = number.find_first_not_of("0123456789");
      if (it->second != who && digits > 0 && digits != std::string::npos &&
          number.substr(digits) == ".pli")
        throw Error(ErrorClass::usage, "options",
                    "'" + it->first + "' would be written by " + it->second + " and by " + who +
                        " (its .pli's numbered files, one per open segment): make the -o "
                        "templates give each region its own files");
    }
}

// Runs `run` for every region, `jobs` at once; a failure (Error) is reported in its
// console and the others go on. With `table_path`, its CSV is written as each region
// ends and once more at the end; then the table and the total ("M of N `done`") on the
// console. The exit code is the first failure's.
int run_each(const CommonArgs& a, const std::string& option, const std::string& field,
             std::vector<EachRegion>& regions, int jobs, const std::string& done,
             const std::string& table_path,
             const std::function<RegionOutcome(EachRegion&, const Console&)>& run) {
  if (has_each_mark(table_path))
    throw Error(ErrorClass::usage, "options",
                "--each-table is one file for the whole batch, without {}: '" + table_path + "'");
  std::vector<std::string> values;
  for (const EachRegion& r : regions) values.push_back(r.value);
  auto header = [&](std::size_t k) -> std::string {
    if (a.quiet) return "";
    return "== " + field + " = " + values[k] + " (" + std::to_string(k + 1) + " of " +
           std::to_string(values.size()) + ")\n";
  };
  auto region = [&](std::size_t k, const Console& console) {
    try {
      return run(regions[k], console);
    } catch (const Error& e) {
      if (console.progress) end_progress_line();
      console.err << "isoquad: " << field << " = " << values[k] << ": " << e.what() << "\n";
      RegionOutcome outcome;
      outcome.exit = exit_code(e.error_class());
      outcome.error = e.what();
      if (e.error_class() == ErrorClass::usage) outcome.usage_error = e.what();
      return outcome;
    }
  };
  // The table is written again as each region ends, so that a batch stopped part-way
  // (Ctrl-C) leaves the rows of the regions done, the others `not run`; a failure to write
  // it then is left to the last write, after the batch.
  std::vector<EachCsvRegion> rows;
  for (const EachRegion& r : regions) rows.push_back({r.value, r.name, r.null});
  bool table_written = false, types_written = false, table_failed = false;
  // The column types first: a table on disk always has them beside it.
  auto write_table = [&](const std::vector<RegionOutcome>& outcomes) {
    const std::string types = each_csv_types_path(table_path);
    if (!types.empty() && !types_written) {
      write_text_file(types, format_each_csv_types(), a.overwrite);
      types_written = true;
    }
    write_text_file(table_path, format_each_csv(field, rows, outcomes, done),
                    a.overwrite || table_written);
    table_written = true;
  };
  auto finished = [&](const std::vector<RegionOutcome>& outcomes) {
    if (table_path.empty() || table_failed) return;
    try {
      write_table(outcomes);
    } catch (const Error&) {
      table_failed = true;
    }
  };
  const std::vector<RegionOutcome> outcomes = run_regions(
      regions.size(), static_cast<std::size_t>(jobs), header, region, std::cerr, finished);
  const int exit = each_exit_code(outcomes);
  if (!table_path.empty()) write_table(outcomes);
  if (!a.quiet) std::cerr << format_each_table(field, values, outcomes);
  if (!a.quiet || exit)
    std::cerr << (exit ? "isoquad: " : "")
              << format_each_total(field, values, outcomes, done, option);
  std::cerr << std::flush;
  return exit;
}

// --each FIELD: run_mesh once per region (each_regions). Every region's outputs are
// checked before any meshing.
int run_mesh_each(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m,
                  const std::string& command_line) {
  if (!m.stop_after.empty())
    throw Error(ErrorClass::usage, "options", "--each meshes: no --stop-after");
  const VectorDatasetPool pool;  // INPUT and the other vector files read once, not per region
  if (!m.each.empty() && !m.each_clip.empty())
    throw Error(ErrorClass::usage, "options",
                "--each runs over INPUT's features, --each-clip over --clip's polygons: give one");
  const bool over_clip = !m.each_clip.empty();
  const std::string& field = over_clip ? m.each_clip : m.each;
  std::vector<EachRegion> regions = each_regions(a, f, field, over_clip);
  // A resumed batch (--skip-existing) writes its table again.
  CommonArgs table_args = a;
  table_args.overwrite = a.overwrite || m.skip_existing;
  check_each_table(m.each_table, table_args.overwrite);
  std::vector<std::vector<MeshOutput>> outputs;
  for (EachRegion& r : regions) outputs.push_back(mesh_outputs(r.a, m));
  check_regions_write_apart(regions, outputs, field, m.each_table);
  for (std::size_t k = 0; k < regions.size(); ++k) {
    EachRegion& r = regions[k];
    r.skip = m.skip_existing && every_output_exists(r.a, r.f, m);
    if (r.skip) continue;
    if (m.skip_existing) check_not_partly_written(r.a, r.f, m);
    if (!r.a.report_path.empty()) check_output_path(r.a.report_path, a.overwrite);
    if (!r.f.plot_path.empty()) check_output_path(r.f.plot_path, a.overwrite);
    check_mesh_outputs(outputs[k], mesh_write_options(m));
  }
  return run_each(table_args, over_clip ? "--each-clip" : "--each", field, regions, m.jobs,
                  "meshed", m.each_table, [&](EachRegion& r, const Console& console) {
                    if (r.skip) {
                      if (!a.quiet)
                        console.out << "skipped: every output exists (--skip-existing)\n";
                      RegionOutcome outcome;
                      outcome.skipped = true;
                      // The table's figures from the region's report, when it has one.
                      if (!r.a.report_path.empty() && r.a.report_path != "-")
                        outcome.quality = read_report_quality(r.a.report_path);
                      return outcome;
                    }
                    MeshArgs mm = m;
                    try {
                      return run_mesh(r.a, r.f, mm,
                                      command_line +
                                          (over_clip ? " [--each-clip: " : " [--each: ") +
                                          r.filter + "]",
                                      console);
                    } catch (const Error& e) {
                      // A region that fails keeps the files an earlier run wrote, which a
                      // later --skip-existing would take for this run's: say which.
                      std::vector<std::string> earlier;
                      std::error_code ec;
                      for (const MeshOutput& o : outputs[r.index])
                        for (const std::string& f : mesh_output_files(o))
                          if (std::filesystem::exists(f, ec)) earlier.push_back(f);
                      if (!r.a.report_path.empty() && r.a.report_path != "-" &&
                          std::filesystem::exists(r.a.report_path, ec))
                        earlier.push_back(r.a.report_path);
                      if (earlier.empty()) throw;
                      std::string list;
                      for (std::size_t i = 0; i < earlier.size() && i < 3; ++i)
                        list += (i ? ", '" : "'") + earlier[i] + "'";
                      if (earlier.size() > 3)
                        list += " and " + std::to_string(earlier.size() - 3) + " more";
                      throw Error(e.error_class(), e.stage(),
                                  e.message() +
                                      "; its files of an earlier run stay as they were (" + list +
                                      "): remove them, or --skip-existing would count the "
                                      "region done");
                    }
                  });
}

// quality --each FIELD: each region's mesh ({} in --mesh) measured against its fields.
int run_quality_each(const CommonArgs& a, const FieldArgs& f, const QualityArgs& q,
                     const std::string& command_line) {
  if (!has_each_mark(q.mesh_path))
    throw Error(ErrorClass::usage, "options",
                "with --each, --mesh needs {} for the value (e.g. --mesh out/{}.gr3): '" +
                    q.mesh_path + "' has none");
  if (a.input.empty())
    throw Error(ErrorClass::usage, "options",
                "--each selects regions from INPUT's features: give INPUT");
  const VectorDatasetPool pool;
  std::vector<EachRegion> regions = each_regions(a, f, q.each);
  check_each_table(q.each_table, a.overwrite);
  std::vector<std::vector<MeshOutput>> outputs;
  for (const EachRegion& r : regions) {
    outputs.emplace_back();
    for (const std::string& o : r.a.outputs) outputs.back().push_back(MeshOutput{o, "", false});
  }
  check_regions_write_apart(regions, outputs, q.each, q.each_table);
  return run_each(a, "--each", q.each, regions, q.jobs, "measured", q.each_table,
                  [&](EachRegion& r, const Console& console) {
                    QualityArgs qq = q;
                    qq.mesh_path = fill_each_mark(q.mesh_path, r.name);
                    return run_quality(r.a, r.f, qq, command_line + " [--each: " + r.filter + "]",
                                       console);
                  });
}

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
    app.parse(argc, argv);
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

  // Before any thread starts (the signals' own, the stages' helpers): the heap's pools,
  // then the signals every thread blocks, so that Ctrl-C or a batch system's SIGTERM
  // leaves no temporary file.
  limit_heap_arenas(mesh_cmd->parsed()      ? mesh_extra.jobs
                    : quality_cmd->parsed() ? quality_extra.jobs
                                            : 1);
  isoquad::remove_unfinished_outputs_on_signals();
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
      if (!mesh_args.quiet) std::cerr << "skipped: every output exists (--skip-existing)\n";
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
