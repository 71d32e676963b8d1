// The isoquad subcommands' jobs (cli_jobs.h).
#include "cli_jobs.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/command_record.h"
#include "app/fields_job.h"
#include "app/mesh_job.h"
#include "app/mesh_outputs.h"
#include "app/quality_job.h"
#include "app/summary.h"
#include "app/versions.h"
#include "core/error.h"
#include "core/stage_clock.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/read_mesh.h"
#include "gis/read_size_features.h"
#include "gis/write_domain.h"
#include "io/write_fields.h"
#include "io/write_mesh.h"
#include "plot/plot_fields.h"
#include "plot/plot_mesh.h"

namespace isoquad::cli {

namespace {

// A progress line is on the terminal without its newline: a message must clear it first.
std::atomic<bool> progress_line_open{false};

}  // namespace

void end_progress_line() {
  if (progress_line_open.exchange(false)) std::fprintf(stderr, "\r\033[K");
}

namespace {

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

}  // namespace

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
    throw Error(ErrorClass::usage, "options",
                "'" + a.output + "': the fields are written as .vtu or .gpkg");
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
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    std::cerr << format_domain_summary(r.front.summary) << format_fields_summary(r);
    std::cerr << "output:       " << a.output << (f.plot_path.empty() ? "" : ", " + f.plot_path)
              << "\n";
    std::fprintf(stderr, "time:         %.3f s\n", seconds);
    for (const std::string& w : r.front.summary.warnings)
      std::cerr << "isoquad: warning: " << w << "\n";
  }
  return 0;
}

std::string joined_command_line(int argc, char** argv) {
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
    s += " " + shell_quoted(arg);
  }
  return s;
}

std::vector<std::string> skipped_outputs_warnings(const CommonArgs& a, const MeshArgs& m,
                                                  const std::string& command_line,
                                                  std::vector<std::string>* unreadable_files) {
  std::vector<std::string> unreadable, warnings;
  const std::optional<RecordedCommand> recorded =
      recorded_command(mesh_outputs(a, m), a.report_path, &unreadable);
  if (unreadable_files) *unreadable_files = unreadable;
  for (const std::string& file : unreadable)
    warnings.push_back("'" + file +
                       "' does not read as isoquad's (damaged, cut short, or another "
                       "program's): it is kept as it is; --overwrite meshes again");
  if (!recorded || recorded->command == command_line) return warnings;
  // A region is its value's features, recorded by their ids after the command, whichever
  // --where (--clip-where) listed them.
  std::vector<std::string> ignored;
  if (!m.each.empty()) ignored.push_back("--where");
  if (!m.each_clip.empty()) ignored.push_back("--clip-where");
  const std::string difference =
      command_difference(recorded->command, command_line, m.option_shapes, ignored);
  if (!difference.empty())  // else the same options, in another order or spelling
    warnings.push_back("'" + recorded->file + "' was written by another command (" + difference +
                       "): its outputs are kept as they are; --overwrite meshes again with "
                       "this one");
  return warnings;
}

RegionOutcome run_mesh(CommonArgs& a, FieldArgs& f, MeshArgs& m, const std::string& command_line,
                       const Console& console) {
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
    throw Error(ErrorClass::usage, "options",
                "--stop-after needs --plot or --report to show the tiling");
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

RegionOutcome run_quality(CommonArgs& a, FieldArgs& f, const QualityArgs& q,
                          const std::string& command_line, const Console& console) {
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
                                                       {!a.fe.read.src_crs.empty(), "--src-crs"},
                                                       {a.fe.read.zmin.has_value(), "--zmin"},
                                                       {a.fe.read.zmax.has_value(), "--zmax"}};
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
    data.vertex_ids = r.point_ids;
    data.quad_ids = r.quad_ids;
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

}  // namespace isoquad::cli
