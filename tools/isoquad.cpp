// isoquad command-line interface: parses arguments into option structs and calls the
// library. Every failure maps to one exit code (see kExitCodes below and README.md).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <filesystem>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "app/front_end.h"
#include "app/summary.h"
#include "core/error.h"
#include "gis/atomic_output.h"
#include "gis/write_domain.h"

namespace {

using namespace isoquad;

const char* kExitCodes =
    "Exit codes:\n"
    "  0   success\n"
    "  2   usage: bad command line or option value\n"
    "  3   input: missing, unreadable or invalid input data, empty selection\n"
    "  4   crs: missing or unknown CRS, coordinates outside the CRS's valid range\n"
    "  5   meshing: a meshing stage failed\n"
    "  6   output: output exists (see --overwrite) or cannot be written\n"
    "  70  internal error (a bug: please report it)\n";

struct CommonArgs {
  std::string input;
  std::string output;
  std::string bbox;
  std::string domain_kind = "land";
  double simplify_m = -1.0;
  double min_island_area_m2 = -1.0;
  std::string report_path;
  bool overwrite = false;
  bool quiet = false;
  FrontEndOptions fe;
};

void add_front_end_options(CLI::App* cmd, CommonArgs& a) {
  cmd->add_option("INPUT", a.input, "Input vector file (shapefile, GeoJSON, TopoJSON, GeoPackage...)")
      ->required();
  cmd->add_option("-o,--output", a.output, "Output file (.gpkg)")->required();
  cmd->add_option("--layer", a.fe.read.layer, "Layer to read (default: the only layer, or the first with polygons)")
      ->group("Selection");
  cmd->add_option("--where", a.fe.read.where, "OGR SQL attribute filter, e.g. \"name = 'France'\"")
      ->group("Selection");
  cmd->add_option("--bbox", a.bbox, "XMIN,YMIN,XMAX,YMAX in the source CRS (or --bbox-crs)")
      ->group("Selection");
  cmd->add_option("--bbox-crs", a.fe.read.bbox_crs, "CRS of --bbox (default: the source CRS)")
      ->group("Selection");
  cmd->add_option("--domain", a.domain_kind,
                  "land: inside the polygons (clipped to --bbox); water: --bbox minus the polygons")
      ->check(CLI::IsMember({"land", "water"}))
      ->group("Selection");
  cmd->add_flag("--largest", a.fe.largest, "Keep only the largest component")->group("Selection");
  cmd->add_option("--src-crs", a.fe.read.src_crs,
                  "CRS of the input coordinates (required when the input has none; overrides it)")
      ->group("Projection");
  cmd->add_option("--dst-crs", a.fe.project.dst_crs,
                  "Meshing CRS, projected in metres (default: a local oblique stereographic "
                  "projection centred on the domain)")
      ->group("Projection");
  cmd->add_flag("--repair", a.fe.read.repair,
                "Repair invalid geometry (self-intersections, unclosed or degenerate rings) "
                "instead of failing")
      ->group("Cleaning");
  cmd->add_option("--size", a.fe.target_size_m,
                  "Target element size in metres; sets the defaults of --simplify (size/4) and "
                  "--min-island-area (size^2)")
      ->check(CLI::PositiveNumber)
      ->group("Cleaning");
  cmd->add_option("--simplify", a.simplify_m,
                  "Topology-preserving simplification tolerance in metres (default: --size/4, or off)")
      ->check(CLI::NonNegativeNumber)
      ->group("Cleaning");
  cmd->add_option("--min-island-area", a.min_island_area_m2,
                  "Drop islands and holes smaller than this, in m2 (default: --size^2, or 0)")
      ->check(CLI::NonNegativeNumber)
      ->group("Cleaning");
  cmd->add_option("--report", a.report_path, "Write the summary as JSON to this file")->group("Output");
  cmd->add_flag("--overwrite", a.overwrite, "Replace existing output files")->group("Output");
  cmd->add_flag("-q,--quiet", a.quiet, "Print nothing but errors")->group("Output");
}

std::array<double, 4> parse_bbox(const std::string& text) {
  std::array<double, 4> b{};
  std::stringstream ss(text);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n == 4) break;
    char* end = nullptr;
    b[n] = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0')
      throw Error(ErrorClass::usage, "options", "--bbox: '" + item + "' is not a number");
    ++n;
  }
  if (n != 4 || std::getline(ss, item, ','))
    throw Error(ErrorClass::usage, "options", "--bbox needs four numbers: XMIN,YMIN,XMAX,YMAX");
  return b;
}

// Renders progress on stderr, throttled, only when stderr is a terminal.
ProgressCallback make_progress(bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return nullptr;
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  return [last](const std::string& stage, double f) {
    const auto now = std::chrono::steady_clock::now();
    if (f < 1.0 && now - *last < std::chrono::milliseconds(100)) return true;
    *last = now;
    std::fprintf(stderr, "\r%-12s %3d%%%s", stage.c_str(), static_cast<int>(f * 100 + 0.5),
                 f >= 1.0 ? "\n" : "");
    std::fflush(stderr);
    return true;
  };
}

void finish_front_end_args(CommonArgs& a) {
  a.fe.read.path = a.input;
  if (!a.bbox.empty()) a.fe.read.bbox = parse_bbox(a.bbox);
  a.fe.kind = a.domain_kind == "water" ? DomainKind::water : DomainKind::land;
  if (a.simplify_m >= 0) a.fe.simplify_m = a.simplify_m;
  if (a.min_island_area_m2 >= 0) a.fe.min_island_area_m2 = a.min_island_area_m2;
}

void write_text_atomically(const std::string& path, const std::string& text, bool overwrite) {
  AtomicOutput out(path, overwrite);
  {
    std::ofstream f(out.temp_path());
    f << text;
    f.close();
    if (!f) throw Error(ErrorClass::output, "write", "'" + path + "': cannot write");
  }
  out.commit();
}

int run_domain(CommonArgs& a) {
  finish_front_end_args(a);
  // Fail before any work when an output cannot be written.
  check_output_path(a.output, a.overwrite);
  if (!a.report_path.empty()) check_output_path(a.report_path, a.overwrite);
  const std::string ext = std::filesystem::path(a.output).extension().string();
  if (ext != ".gpkg" && ext != ".GPKG")
    throw Error(ErrorClass::usage, "options",
                "'" + a.output + "': the domain is written as a GeoPackage; use a .gpkg name");

  const auto t0 = std::chrono::steady_clock::now();
  FrontEndResult r = build_planar_domain(a.fe, Progress(make_progress(a.quiet)));
  WriteDomainParams wp;
  wp.path = a.output;
  wp.overwrite = a.overwrite;
  write_domain_gpkg(r.domain, wp);
  if (!a.report_path.empty())
    write_text_atomically(a.report_path, domain_summary_json(r.summary), a.overwrite);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.quiet) {
    std::cout << format_domain_summary(r.summary);
    std::cout << "output:       " << a.output << " (layer 'domain')\n";
    std::printf("time:         %.3f s\n", seconds);
    for (const std::string& w : r.summary.warnings) std::cerr << "isoquad: warning: " << w << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "isoquad: isotropic all-quadrangle meshes of map polygons (coastlines, lakes, sea "
      "areas) that follow a sizing field and a cross field."};
  app.footer(kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("isoquad ") + ISOQUAD_VERSION);

  CommonArgs domain_args;
  CLI::App* domain_cmd = app.add_subcommand(
      "domain",
      "Read, select, project, repair and simplify polygons; write the planar domain (in the "
      "meshing CRS) as a GeoPackage and print a summary.");
  add_front_end_options(domain_cmd, domain_args);
  domain_cmd->footer(kExitCodes);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "isoquad: usage: " << e.what() << "\nRun 'isoquad --help' for the options.\n";
    return exit_code(ErrorClass::usage);
  }

  try {
    if (domain_cmd->parsed()) return run_domain(domain_args);
  } catch (const Error& e) {
    std::cerr << "isoquad: " << e.what() << "\n";
    return exit_code(e.error_class());
  } catch (const std::exception& e) {
    std::cerr << "isoquad: internal error: " << e.what() << "\n";
    return exit_code(ErrorClass::internal);
  }
  return exit_code(ErrorClass::usage);
}
