#include "cli_args.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

#include "app/mesh_outputs.h"
#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/raster_field.h"
#include "gis/read_mesh.h"
#include "gis/sample_field.h"
#include "gis/where_hint.h"

namespace isoquad::cli {

namespace {

// Lengths on the ground beyond this (two and a half times round the Earth) are mistakes,
// and their squares and sums would overflow.
constexpr double kLongestLength = 1e8;

// Number checks with plain messages (CLI11's own name the whole double range); a length
// in metres is also at most kLongestLength.
CLI::Validator number_check(const char* name, bool zero_allowed, bool length = false) {
  return CLI::Validator(
      [zero_allowed, length](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v))
          return "'" + text + "' is not a number";
        if (zero_allowed ? v < 0 : !(v > 0))
          return "must be " + std::string(zero_allowed ? "0 or more" : "more than 0") + ", not " +
                 text;
        // Subnormal numbers (4.9e-324) underflow in the first product.
        if (v != 0 && !std::isnormal(v)) return "'" + text + "' is too small a number";
        if (length && v > kLongestLength)
          return text + " m is longer than 100,000 km, more than twice round the Earth";
        return {};
      },
      name);
}

// A file name that ends in `extension` (any case): the plots are PNG only.
CLI::Validator extension_check(const std::string& extension) {
  return CLI::Validator(
      [extension](std::string& text) -> std::string {
        std::string ext = std::filesystem::path(text).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext == extension) return {};
        return "'" + text + "': the plot is a PNG image; name it " + extension;
      },
      "");
}

const CLI::Validator kPositive = number_check("POSITIVE", false);
const CLI::Validator kNonNegative = number_check("NONNEGATIVE", true);
const CLI::Validator kPositiveLength = number_check("POSITIVE", false, true);
const CLI::Validator kNonNegativeLength = number_check("NONNEGATIVE", true, true);

std::array<double, 4> parse_bbox(const std::string& text) {
  std::array<double, 4> b{};
  std::stringstream ss(text);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n == 4)
      throw Error(ErrorClass::usage, "options", "--bbox needs four numbers: XMIN,YMIN,XMAX,YMAX");
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

}  // namespace

std::vector<std::string> checked_arguments(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  // The subcommand: the first word that is not an option.
  const CLI::App* sub = nullptr;
  std::size_t first = 0;
  while (first < args.size() && !args[first].empty() && args[first][0] == '-') ++first;
  if (first < args.size())
    for (const CLI::App* s : app.get_subcommands({}))
      if (s->get_name() == args[first]) sub = s;
  ++first;  // the options from the word after it
  if (!sub) {
    // A word where the subcommand should be: a misspelt one, or `help mesh`.
    const auto word = std::find_if(args.begin(), args.end(),
                                   [](const std::string& a) { return !a.empty() && a[0] != '-'; });
    if (word == args.end()) return args;
    std::vector<std::string> subs;
    for (const CLI::App* s : app.get_subcommands({})) subs.push_back(s->get_name());
    std::string list;
    for (const std::string& n : subs) list += (list.empty() ? "" : ", ") + n;
    std::vector<std::string> near = nearest_values(*word, subs, 1);
    for (const std::string& n : subs) {  // letters swapped (mseh)
      std::string a = lower_case(*word), b = n;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      if (near.empty() && a == b) near.push_back(n);
    }
    const bool help = *word == "help" && word + 1 != args.end() &&
                      std::find(subs.begin(), subs.end(), *(word + 1)) != subs.end();
    throw CLI::ValidationError("'" + *word + "'",
                               "not a subcommand (" + list + ")" +
                                   (help ? "; for help: isoquad " + *(word + 1) + " --help"
                                    : !near.empty() ? "; did you mean " + near[0] + "?"
                                                    : ""));
  }
  // Its options that take values, and all its options' names.
  std::vector<std::string> valued, names;
  for (const CLI::Option* o : sub->get_options()) {
    std::vector<std::string> own;
    for (const std::string& n : o->get_lnames()) own.push_back("--" + n);
    for (const std::string& n : o->get_snames()) own.push_back("-" + n);
    names.insert(names.end(), own.begin(), own.end());
    if (o->get_items_expected_max() > 0) valued.insert(valued.end(), own.begin(), own.end());
  }
  auto is = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  std::vector<std::string> out(args.begin(), args.begin() + static_cast<long>(first));
  for (std::size_t i = first; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--") {  // the rest are positional
      out.insert(out.end(), args.begin() + static_cast<long>(i), args.end());
      break;
    }
    const std::size_t eq = a.find('=');
    const std::string name = eq == std::string::npos ? a : a.substr(0, eq);
    if (eq != std::string::npos && is(valued, name) &&
        (eq + 1 == a.size() || a.rfind("--", 0) != 0)) {
      out.push_back(name);  // --opt= and -o=FILE
      out.push_back(a.substr(eq + 1));
      continue;
    }
    out.push_back(a);
    if (eq != std::string::npos || !is(valued, a) || i + 1 >= args.size()) continue;
    const std::string& next = args[i + 1];
    const std::string next_name = next.substr(0, next.find('='));
    if (is(names, next_name))
      throw CLI::ValidationError(a, "needs a value, and the word after it is the option " +
                                        next_name + " (give the value, or leave " + a + " out)");
  }
  return out;
}

void check_option_values(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    for (const CLI::Option* o : sub->get_options()) {
      if (o->count() == 0 || o->get_type_size_max() == 0) continue;  // not given, or a flag
      const std::string type = o->get_type_name();
      const bool number = type.rfind("FLOAT", 0) == 0;
      const bool whole = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
      for (const std::string& v : o->results()) {
        if (v.empty())
          throw CLI::ValidationError(o->get_name(),
                                     "an empty value (give one, or leave the option out)");
        // A whole number in decimal: CLI11 would read 010 as octal 8, and 0x10 as 16.
        const std::size_t digits = v[0] == '+' || v[0] == '-' ? 1 : 0;
        if (whole &&
            (v.size() == digits || v.find_first_not_of("0123456789", digits) != std::string::npos ||
             (v[digits] == '0' && v.size() > digits + 1)))
          throw CLI::ValidationError(o->get_name(), "'" + v +
                                                        "' is not a whole number in decimal "
                                                        "(digits, without leading zeros)");
        if (!number) continue;
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end != '\0' || !std::isfinite(x) ||
            v.find_first_of("xX") != std::string::npos)
          throw CLI::ValidationError(o->get_name(), "'" + v + "' is not a number");
      }
    }
}

void add_front_end_options(CLI::App* cmd, CommonArgs& a) {
  CLI::Option* input = cmd->add_option(
      "INPUT", a.input,
      std::string("Input vector file (shapefile, GeoJSON, TopoJSON, GeoPackage...) of polygons, "
                  "or of lines whose rings make them (a coastline drawn as lines; also "
                  "Delft3D/D-Flow FM .ldb, .pol, .pli and Blue Kenue .i2s, with --src-crs), or a "
                  "mesh whose outline is the domain (.gr3 or .ll with its open boundaries, .14, "
                  ".2dm, .msh, .mesh, .nc, .slf, .vtu, .vtk), or a raster (a DEM: GeoTIFF, "
                  "netCDF...) whose cells "
                  "in [--zmin, --zmax] are the domain") +
          (a.input_optional ? "; leave it out to measure against the mesh's own outline" : ""));
  if (!a.input_optional) input->required();
  CLI::Option* output =
      cmd->add_option("-o,--output", a.outputs,
                      a.output_optional ? "Also write the measured quads with their metrics "
                                          "(.gpkg, .vtu, .geojson or .fgb)"
                      : a.many_outputs
                          ? "Output file (.gpkg, .vtu, .vtk, .msh, .gr3, .nc, .2dm, .mesh, "
                            ".pli, .slf, .14; the quads alone: .geojson, .fgb); repeat for "
                            "several; required but with --stop-after"
                      : cmd->get_name() == "domain" ? "Output file (.gpkg, .fgb or .geojson)"
                                                    : "Output file (.gpkg or .vtu)")
          ->expected(1)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
          ->allow_extra_args(false);
  // mesh's -o is checked after parsing (finish_front_end_args): --stop-after writes none.
  if (!a.output_optional && !a.many_outputs) output->required();
  cmd->add_option("--layer", a.fe.read.layer,
                  "Layer to read (default: the only layer, or the first with polygons)")
      ->group("Selection");
  cmd->add_option("--where", a.fe.read.where, "OGR SQL attribute filter, e.g. \"name = 'France'\"")
      ->group("Selection");
  cmd->add_option("--bbox", a.bbox, "XMIN,YMIN,XMAX,YMAX in the source CRS (or --bbox-crs)")
      ->group("Selection");
  cmd->add_option("--bbox-crs", a.fe.read.bbox_crs, "CRS of --bbox (default: the source CRS)")
      ->group("Selection");
  cmd->add_option("--clip", a.fe.clip_path,
                  "Vector file (any format, with a CRS) of one polygon, the area to mesh, in place "
                  "of --bbox: land inside it, or water: it minus the polygons, its edge open (sea) "
                  "where it is not land, or sea: the polygons inside it, its edge open where it "
                  "cuts them")
      ->group("Selection");
  cmd->add_option("--clip-layer", a.fe.clip_layer,
                  "Layer of --clip to read (default: its first layer with polygons)")
      ->group("Selection");
  cmd->add_option("--clip-where", a.fe.clip_where,
                  "OGR SQL filter picking the area among the polygons of --clip, e.g. \"name = "
                  "'Loire'\"")
      ->group("Selection");
  cmd->add_option(
         "--exclude", a.fe.exclude_path,
         "Vector file (any format; in its CRS, else the INPUT's) of polygons whose area "
         "is not meshed: removed from the domain, their edges land (breakwaters, piers "
         "and jetties drawn apart from the coast, a lake's islands kept in another "
         "layer); only those in the area of --bbox or --clip (else in the domain's box) are "
         "read")
      ->group("Selection");
  cmd->add_option("--exclude-layer", a.fe.exclude_layer,
                  "Layer of --exclude to read (default: the only one, or its first with polygons)")
      ->group("Selection");
  cmd->add_option("--exclude-where", a.fe.exclude_where,
                  "OGR SQL filter picking some of the polygons of --exclude, e.g. \"type = "
                  "'breakwater'\"")
      ->group("Selection");
  cmd->add_option("--domain", a.domain_kind,
                  "land: inside the polygons (clipped to --bbox or --clip); water: --bbox (or "
                  "--clip) minus the polygons, open where it is not land; sea: inside the "
                  "polygons, which are water (sea areas, an ocean layer), open where --bbox "
                  "or --clip cuts them")
      ->check(CLI::IsMember({"land", "water", "sea"}))
      ->group("Selection");
  cmd->add_option("--zmin", a.fe.read.zmin,
                  "With a raster INPUT (a DEM): the domain is where its values are at least "
                  "this (and at most --zmax)")
      ->group("Selection");
  cmd->add_option("--zmax", a.fe.read.zmax,
                  "With a raster INPUT (a DEM): the domain is where its values are at most this "
                  "(a sea of elevations: 0; a floodplain: 10), bounded by that contour, open "
                  "where it reaches the raster's edge (or --bbox's, --clip's)")
      ->group("Selection");
  cmd->add_flag("--largest", a.fe.largest, "Keep only the largest component")->group("Selection");
  cmd->add_option("--src-crs", a.fe.read.src_crs,
                  "CRS of the input coordinates (required when the input has none; overrides it)")
      ->group("Projection");
  cmd->add_option("--dst-crs", a.fe.project.dst_crs,
                  "Meshing CRS, projected in metres. Default: the input's own CRS when it is "
                  "projected in metres, conformal and within 1% of the ground's scale over the "
                  "domain (UTM in its zone, a national conformal CRS), else a local oblique "
                  "stereographic projection centred on the domain, which 'local' asks for "
                  "whatever the input; 'utm': the UTM zone of the domain's centre (WGS 84), "
                  "with a warning where the domain reaches beyond the zone's 1% of scale")
      ->group("Projection");
  cmd->add_flag("--repair", a.fe.read.repair,
                "Repair invalid geometry (self-intersections, unclosed or degenerate rings) "
                "instead of failing")
      ->group("Cleaning");
  cmd->add_option("--size", a.fe.target_size_m,
                  "Element size in metres: a constant size for meshing; sets the defaults of "
                  "--simplify (size/4), --min-island-area (size^2) and --min-width (size/4)")
      ->check(kPositiveLength)
      ->group("Cleaning");
  cmd->add_option("--simplify", a.simplify_m,
                  "Topology-preserving simplification tolerance in metres (default: a quarter of "
                  "--size or, in fields and mesh, of the automatic hmin; otherwise off)")
      ->check(kNonNegativeLength)
      ->group("Cleaning");
  cmd->add_option("--min-island-area", a.min_island_area_m2,
                  "Drop islands and holes smaller than this, in m2 (default: the square of --size "
                  "or, in fields and mesh, of the automatic hmin; otherwise 0)")
      ->check(kNonNegative)
      ->group("Cleaning");
  cmd->add_option(
         "--min-width", a.min_width_m,
         "Fill notches and slits, and remove spikes, narrower than this, in m, where that "
         "changes no topology (an isthmus is never cut, two components never joined); cut "
         "back tips sharper than 15 degrees to this width (default: a quarter of --size or, "
         "in fields and mesh, of the automatic hmin; otherwise off)")
      ->check(kNonNegativeLength)
      ->group("Cleaning");
  cmd->add_option("--hairline", a.hairline_m,
                  "Of the pieces narrower than --min-width that it keeps because filling or "
                  "cutting them would join or cut components or holes: close the gaps, and cut "
                  "out the strips, narrower than this, in m (polygons that miss each other by a "
                  "hair: unsnapped neighbours, tiles), which would need quads that narrow "
                  "(default: a fiftieth of --min-width; 0: never)")
      ->check(kNonNegativeLength)
      ->group("Cleaning");
  cmd->add_option("--report", a.report_path,
                  "Write the summary as JSON to this file (-: to stdout, once every output is "
                  "written)")
      ->group("Output");
  cmd->add_flag("--overwrite", a.overwrite, "Replace existing output files")->group("Output");
  cmd->add_flag("-q,--quiet", a.quiet, "Print nothing but errors")->group("Output");
}

void add_quality_options(CLI::App* cmd, QualityArgs& q) {
  cmd->add_option("--mesh", q.mesh_path,
                  "The mesh to measure: SCHISM .gr3 or .ll, ADCIRC .14, SMS .2dm, Gmsh .msh "
                  "(ASCII 2.2 or 4.1), MIKE .mesh, UGRID .nc (also D-Flow FM's net files), "
                  "TELEMAC .slf, VTK .vtu or .vtk (ASCII), or polygons (isoquad's .gpkg, .shp, "
                  ".geojson, .fgb); "
                  "triangles and quadrangles")
      ->required()
      ->group("Mesh");
  cmd->add_option("--mesh-crs", q.mesh_crs,
                  "CRS of the mesh's coordinates (EPSG:4326 for a .14 in longitudes and "
                  "latitudes; default: the file's own (.ll, .mesh, .nc, polygons, a .gr3 whose "
                  "title names it, as isoquad's do), else the "
                  "meshing CRS, as --dst-crs or the automatic projection gives it)")
      ->group("Mesh");
  cmd->add_option("--each", q.each,
                  "A mesh measured per value of this attribute over the selected features (each "
                  "value's features together): {} in --mesh, -o, --report and --plot stands for "
                  "the value; a region that fails does not stop the others, unless two fail with "
                  "the same usage error (the command's)")
      ->group("Selection");
  cmd->add_option("--jobs", q.jobs,
                  "With --each: regions measured at once, each on its own thread (default 1)")
      ->check(kPositive)
      ->group("Selection");
  cmd->add_option("--each-table", q.each_table,
                  "With --each: the closing table as a CSV file, a row per region in order "
                  "(status, exit code, the quality figures, the error of a failed one; no "
                  "seconds, so that the same batch writes the same bytes); written again as "
                  "each region ends")
      ->group("Selection");
}

void add_field_options(CLI::App* cmd, FieldArgs& f) {
  const char* g = "Sizing (metres; sources combine by minimum)";
  cmd->add_flag("--size-auto", f.size_auto,
                "Automatic size from the boundary's local feature size (the default when no "
                "other source is given; with another source, both combine)")
      ->group(g);
  cmd->add_option("--size-expr", f.sizing.expression,
                  "Size as an expression in x and y (metres, meshing CRS), e.g. "
                  "\"0.01*(2+sin(6*x*pi-pi/2))\", lon and lat (degrees), e.g. \"lat > 48.3 ? "
                  "500 : 2000\", and d, the depth in metres (positive down, "
                  "from --bathymetry or --elevation; the expression holds where they give one), "
                  "e.g. \"d < 20 ? 500 : min(5000, 25*d)\", and c, the distance to the coast in "
                  "metres (the boundary but its open parts), e.g. \"500 + 0.1*c\"")
      ->group(g);
  cmd->add_option("--size-raster", f.sizing.raster_path, "GDAL raster of sizes in metres, any CRS")
      ->group(g);
  cmd->add_option(
         "--size-mesh", f.sizing.size_mesh_path,
         "A mesh whose elements give the sizes (a model's grid: .gr3, .ll, .14, .2dm, "
         ".msh, .mesh, .nc, .slf, .vtu, .vtk): each node's mean side length, linear between "
         "nodes; in the file's CRS, else --src-crs, else the meshing CRS")
      ->group(g);
  cmd->add_option("--refine", f.sizing.refine_path,
                  "Vector file (any format, with a CRS) of polygons, lines or points whose "
                  "attribute --refine-field gives a size in metres: at most that inside the "
                  "polygons and on the lines and points, growing by --gradation away from "
                  "them (not limited by --hmin)")
      ->group(g);
  cmd->add_option("--refine-field", f.sizing.refine_field,
                  "Attribute of --refine holding the sizes (default: size)")
      ->group(g);
  cmd->add_option("--refine-width-field", f.sizing.refine_width_field,
                  "Attribute of --refine holding widths in metres: the size holds within half "
                  "the width of each feature's lines, points and polygons, and grows by "
                  "--gradation beyond (default: none, the size on the features only)")
      ->group(g);
  cmd->add_option("--refine-layer", f.sizing.refine_layer,
                  "Layer of --refine to read (default: its first)")
      ->group(g);
  // --bathymetry and --elevation make one list, in the order given (trigger_on_parse:
  // each occurrence is added as it is read).
  for (const bool elevation : {false, true})
    cmd->add_option_function<std::string>(
           elevation ? "--elevation" : "--bathymetry",
           [&f, elevation](const std::string& path) {
             f.sizing.bathymetry.push_back({path, elevation});
           },
           elevation ? "GDAL raster of elevations in metres, positive up, as GEBCO, EMODnet and "
                       "SRTM15+ give them (-200 is 200 m deep); otherwise as --bathymetry, in the "
                       "same priority list"
                     : "GDAL raster of depths in metres, positive down: vertex depths of the mesh "
                       "outputs; with --wavelength-period, --slope-factor or --time-step also the "
                       "sizing. Repeat it (or --elevation) for several, in priority order (a "
                       "survey, then a regional grid, then GEBCO): at each point the first with a "
                       "depth gives it. A mesh gives its nodes' values: .gr3, .ll, .14 depths; "
                       ".2dm, .mesh, .nc, .slf bed levels, for --elevation. Scattered samples "
                       "(soundings: an .xyz of x y value lines, or a layer of points with Z or "
                       "--depth-field) give values linear between them, up to their outline")
        ->trigger_on_parse()
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
        ->group(g);
  cmd->add_option("--depth-field", f.depth_field,
                  "Attribute holding the values of points given as --bathymetry or --elevation "
                  "(default: their Z)")
      ->group(g);
  cmd->add_option("--depth-crs", f.depth_crs,
                  "CRS of --bathymetry and --elevation files that do not say theirs (an .xyz, a "
                  ".gr3, .14 or .2dm; default: --src-crs)")
      ->group(g);
  cmd->add_option("--min-depth", f.min_depth_m,
                  "Depths shallower than this (metres, positive down) are written as it; the "
                  "wavelength, slope and time step rules count depths under max(1, this) as that")
      ->group(g);
  cmd->add_option("--wavelength-period", f.sizing.wavelength_period_s,
                  "Wave period T in seconds: h <= T sqrt(g d) / N")
      ->check(kPositive)
      ->group(g);
  cmd->add_option("--cells-per-wavelength", f.sizing.cells_per_wavelength,
                  "N of the wavelength rule")
      ->check(kPositive)
      ->group(g);
  cmd->add_option("--slope-factor", f.sizing.slope_factor,
                  "R: h <= 2 pi d / (R |grad d|), resolving bathymetric slopes")
      ->check(kPositive)
      ->group(g);
  char margin[16];
  std::snprintf(margin, sizeof margin, "%g", kTimeStepMargin);
  cmd->add_option("--time-step", f.sizing.time_step_s,
                  "DT in seconds, with depths: sizes at least " + std::string(margin) +
                      " DT sqrt(g d) / C, so that an explicit model can run at DT (a quad's time "
                      "step is its width over sqrt(g d) times C); over every other source, "
                      "--hmin and --hmax, under --refine")
      ->check(kPositive)
      ->group(g);
  cmd->add_option("--courant", f.sizing.courant,
                  "C, the model's gravity-wave Courant limit, for --time-step and the time "
                  "steps reported (default 1; D-Flow FM's CFLMax is 0.7)")
      ->check(kPositive)
      ->group(g);
  cmd->add_option("--cells-across", f.sizing.cells_across,
                  "Elements across a narrow channel (automatic sizing; default 2)")
      ->check(kPositive)
      ->group(g);
  cmd->add_option("--hmin", f.sizing.hmin_m,
                  "Smallest size (automatic default: hmax / 10); automatic sizing puts one "
                  "element across channels, inlets and spits narrower than --cells-across x "
                  "hmin, down to hmin/2 (see --no-narrow-sizes)")
      ->check(kPositiveLength)
      ->group(g);
  cmd->add_flag_callback(
         "--no-narrow-sizes", [&f] { f.sizing.narrow_sizes = false; },
         "Leave channels narrower than --cells-across x hmin at the sizes around them (hmin "
         "or more): fewer quads, which may fold across them")
      ->group(g);
  cmd->add_option("--hmax", f.sizing.hmax_m,
                  "Largest size (automatic default: sqrt(domain area / 2000))")
      ->check(kPositiveLength)
      ->group(g);
  cmd->add_option("--gradation", f.sizing.gradation,
                  "K: sizes change by at most K metres per metre (default 0.2: a tile 2h wide then "
                  "spans a 40% change of h; larger grades faster with worse quads)")
      ->check(kPositive)
      ->group(g);
  cmd->add_option_function<std::string>(
         "--size-scale", [&f](const std::string& v) { f.sizing.ground_sizes = v == "ground"; },
         "ground (default): sizes in metres are lengths on the ground, multiplied by the meshing "
         "CRS's scale where it strays from 1 by more than 0.5% (a domain reaching more than "
         "about 1,300 km from the automatic projection's centre, an ocean basin, a "
         "Mercator map): quads of the same size on the ground everywhere; crs: lengths in the "
         "meshing CRS's metres, as a model run in those coordinates measures them")
      ->check(CLI::IsMember({"ground", "crs"}))
      ->group(g);
  const char* c = "Cross field";
  cmd->add_option("--cross", f.cross,
                  "boundary (default): cross field tangent to the boundary, smoothest inside up to "
                  "the rotation --cross-conformal asks for")
      ->check(CLI::IsMember({"boundary"}))
      ->group(c);
  cmd->add_option("--cross-angle", f.cross_angle_deg, "Constant cross angle in degrees")
      ->check(CLI::Range(-360.0, 360.0))
      ->group(c);
  cmd->add_option("--cross-raster", f.cross_raster,
                  "GDAL raster of cross angles in degrees (counter-clockwise from the x axis)")
      ->group(c);
  cmd->add_option("--cross-conformal", f.cross_conformal,
                  "F: the boundary field turns, inside, by F times the rotation a conformal grid "
                  "with the sizes has (its singularities go where sizes grade); 0: the smoothest "
                  "field, as the paper (default 0.5)")
      ->check(CLI::Range(0.0, 1.0))
      ->group(c);
  cmd->add_option("--align", f.align_path,
                  "Vector file (any format, with a CRS) of lines inside the domain that the "
                  "cross field follows as it follows the coast: rows of quads run along a "
                  "channel's axis, a breakwater or a shipping lane; quads follow a line best in a "
                  "band of even sizes (--refine on the same file with --refine-width-field)")
      ->group(c);
  cmd->add_option(
         "--align-layer", f.align_layer,
         "Layer of --align to read (default: its first layer of lines, or its first layer)")
      ->group(c);
  cmd->add_option(
         "--background-factor", f.background_factor,
         "Background triangles are at most this fraction of the tile size 2h (default 0.25)")
      ->check(CLI::Range(0.001, 1.0))
      ->group("Background mesh");
  cmd->add_option("--max-quads", f.max_quads,
                  "Stop before meshing when the sizes ask for more quads than this (about 2 to 5 "
                  "KB of memory each; default 1000000; 0: no limit)")
      ->check(kNonNegative)
      ->group("Background mesh");
  cmd->add_option("--plot", f.plot_path, "Also draw a PNG (FILE.png)")
      ->check(extension_check(".png"))
      ->group("Output");
}

// For every subcommand: `domain` (its summary says how much of the boundary the lines
// follow), `fields` (the distance to the coast, c, leaves them out), `mesh` and `quality`
// (the outline's open boundaries, and their summaries' lengths).
void add_open_boundary_options(CLI::App* cmd, FrontEndOptions& fe) {
  cmd->add_option("--open-boundary", fe.open_boundary_path,
                  "Vector file (any format, with a CRS) of lines drawn along the domain's edge "
                  "(or polygons, by their rings): the boundary they follow is open (sea), the "
                  "rest land, in every output; replaces a water domain's bbox sides")
      ->group("Output");
  cmd->add_option("--open-boundary-layer", fe.open_boundary_layer,
                  "Layer of --open-boundary to read (default: its first layer of lines, or its "
                  "first layer)")
      ->group("Output");
  cmd->add_option("--open-groups", fe.open_groups,
                  "With a Gmsh .msh or an SMS .2dm as INPUT: its physical groups of curves or "
                  "nodestrings (names or numbers, comma-separated; nodestrings numbered from 1) "
                  "whose lines along the outline are open boundaries (default: those whose name "
                  "begins with 'open', as isoquad's own .msh names them); for quality without "
                  "INPUT, those of --mesh")
      ->delimiter(',')
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->group("Output");
}

void add_mesh_options(CLI::App* cmd, MeshArgs& m) {
  cmd->add_option("--each", m.each,
                  "A mesh per value of this attribute over the selected features (each value's "
                  "features together; fid: a mesh per feature): {} in -o, --report and --plot "
                  "stands for the value (in a folder's name, -o runs/{}/hgrid.gr3, each region's "
                  "folder is made as its files are written); a "
                  "region that fails does not stop the others, unless two fail with the same "
                  "usage error (the command's)")
      ->group("Selection");
  cmd->add_option("--each-clip", m.each_clip,
                  "A mesh per value of this attribute over the polygons of --clip (each value "
                  "picks its area, as --clip-where would): one land or sea file, many areas "
                  "(bays, estuaries, a model's nested domains); {} as with --each")
      ->group("Selection");
  cmd->add_option("--jobs", m.jobs,
                  "With --each or --each-clip: regions meshed at once, each on its own thread "
                  "(default 1). Every "
                  "region's files are the same; their summaries print in order as they finish, "
                  "without progress; the peak memory is that of the regions running together")
      ->check(kPositive)
      ->group("Selection");
  cmd->add_option(
         "--each-table", m.each_table,
         "With --each or --each-clip: the closing table as a CSV file, a row per region in order "
         "(status, exit code, the quality figures, the error of a failed one; no "
         "seconds, so that the same batch writes the same bytes); written again as each "
         "region ends (a batch stopped part-way leaves the regions done, the others 'not "
         "run') and by a batch resumed with --skip-existing")
      ->group("Selection");
  cmd->add_flag("--skip-existing", m.skip_existing,
                "Mesh nothing where every output (with --report and --plot) exists already: with "
                "--each, those regions are skipped, so that a batch stopped part-way resumes "
                "where it stopped (a run writes all its outputs or none, and removes its "
                "unfinished ones when stopped by Ctrl-C or SIGTERM); a warning names the "
                "options that differ where their report or GeoPackage records another command")
      ->group("Output");
  cmd->add_flag("--embed", m.mesh.embed_lines,
                "With --align: a path of the mesh's edges along each line, its vertices moved "
                "onto the line (breaklines, dyke crests, thin dams), every quad kept convex; the "
                "summary says how much of the lines the edges cover")
      ->group("Cross field");
  cmd->add_option("--embed-points", m.embed_points,
                  "Vector file of points (its first layer of points; a CSV with x and y, lon "
                  "and lat, or easting and northing columns) the mesh gets vertices at: "
                  "stations, a river's source; each point takes a nearest interior vertex, "
                  "moved onto it with every quad kept convex (the summary's `points:` line); "
                  "one nearer the coast than a fifth of a quad, or on the land within a quad of "
                  "it, a vertex on the coast beside it. In the file's CRS, else the INPUT's")
      ->group("Cross field");
  cmd->add_option("--embed-points-name", m.embed_points_name,
                  "Attribute of --embed-points naming each point (a station's name), in the "
                  "summary and the report's embedded_points (default: name, when the layer has "
                  "it)")
      ->group("Cross field");
  const char* g = "Tiling (paper, sections 2.2 to 2.5)";
  cmd->add_option("--init", m.init,
                  "How tiles start: front (default; seeds one tile apart along the cross field, "
                  "row by row from the boundary inwards) or merge (the paper: triangles merged by "
                  "compactness)")
      ->check(CLI::IsMember({"front", "merge"}))
      ->group(g);
  cmd->add_option("--relax-iters", m.mesh.tiling.relax_iters,
                  "Cap on L-infinity relaxation iterations (default 50)")
      ->check(kNonNegative)
      ->group(g);
  cmd->add_option("--conform-iters", m.mesh.tiling.conform_iters,
                  "Conforming relaxation iterations (default 20)")
      ->check(kNonNegative)
      ->group(g);
  cmd->add_option("--conform-shift", m.mesh.tiling.conform_shift,
                  "Generator shift: a fraction of the offset between neighbouring tiles (lattice) "
                  "or of the projected meta-edge length (the other rules) (default 0.2, the "
                  "paper's)")
      ->check(CLI::Range(0.0, 1.0))
      ->group(g);
  cmd->add_option("--butterfly-max", m.mesh.tiling.butterfly_max,
                  "Remove butterflies whose inner meta-edge is shorter than this times h (default "
                  "3; the paper's 0.5 of the tile size 2h is 1)")
      ->check(kNonNegative)
      ->group(g);
  cmd->add_option(
         "--resplit-rounds", m.mesh.tiling.resplit_rounds,
         "After the butterflies, rounds of re-splitting two adjacent tiles into a quadrangle "
         "and the rest (two quadrangles when their union has six meta-vertices), when that leaves "
         "fewer irregular "
         "vertices (default 10; 0: none, as the paper)")
      ->check(kNonNegative)
      ->group(g);
  cmd->add_option("--corner-barrier", m.mesh.tiling.barriers.length_h,
                  "Length, in h, of the edge paths from reflex boundary corners that no tile "
                  "floods across, so that tiles meet at the corner (default 1; 0: none)")
      ->check(kNonNegative)
      ->group(g);
  cmd->add_option(
         "--conform-rule", m.conform_rule,
         "How conforming relaxation shifts a tile: lattice (default; towards the rows and "
         "columns of its neighbours along the cross field), longest-away (the paper: along "
         "the longest meta-edge with one corner end, away from the corner), "
         "longest-towards, or close-shortest (closing the shortest such meta-edge)")
      ->check(CLI::IsMember({"close-shortest", "longest-away", "longest-towards", "lattice"}))
      ->group(g);
  cmd->add_option("--max-attempts", m.mesh.max_attempts,
                  "Tilings tried before giving up where quads fold or stay non-convex, each "
                  "with the sizes halved where the one before failed (default 6)")
      ->check(CLI::Range(1, 100))
      ->group(g);
  cmd->add_option(
         "--corner-angle", m.mesh.tiling.graph.corner_angle_deg,
         "Boundary vertices turning by more than this many degrees are corners (default 45)")
      ->check(CLI::Range(0.0, 180.0))
      ->group(g);
  cmd->add_option(
         "--stop-after", m.stop_after,
         "Stop after a tiling step and plot the tiles: init, relax, conform, butterfly or resplit")
      ->check(CLI::IsMember({"init", "relax", "conform", "butterfly", "resplit"}))
      ->group(g);
  cmd->add_option("--smooth-iters", m.mesh.smooth.iterations,
                  "Laplacian smoothing sweeps (default 10)")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--aligned-iters", m.mesh.smooth.aligned_iterations,
                  "Field-aligned smoothing sweeps after the Laplacian ones: edges pulled to "
                  "length h along the cross field (default 20; 0: none)")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--angle-iters", m.mesh.smooth.angle_iterations,
                  "Angle sweeps last: vertices take small moves that bring corners nearer 90 "
                  "degrees and edges nearer the cross field, keeping sizes (default 20; 0: none)")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--orientation-weight", m.mesh.smooth.angle_orientation_weight,
                  "Weight of the edges' rotation from the cross field in the angle sweeps, "
                  "against square corners and sizes (default 1.5; 0: none). More turns edges "
                  "nearer the field at the cost of angles and sizes; less gives better angles "
                  "(fewer quads under SCHISM's angle ratio)")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--schism-weight", m.mesh.smooth.angle_ratio_weight,
                  "Weight, in the angle sweeps, of each quad whose smallest angle is under half "
                  "its largest (SCHISM's angle ratio check; default 0.5; 0: none). More gives "
                  "fewer such quads at the cost of angles in [75,105] and orientation")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--max-orthogonality", m.mesh.smooth.max_orthogonality,
                  "D-Flow FM: last, the interior corners of quads whose links have an "
                  "orthogonality over this move until they do not, where they can (D-Flow FM "
                  "refuses a network with one over 0.5, its CosPhiuTrsh: 0.45 leaves a margin; "
                  "default 0: none; again after --embed and --embed-points, their vertices "
                  "held). Costs a little of the angles in [75,105]")
      ->check(CLI::Range(0.0, 1.0))
      ->group("Quads");
  cmd->add_option("--coast-weight", m.mesh.smooth.coast_weight,
                  "Weight, in the angle sweeps, of how far the coast between a boundary edge's "
                  "ends lies off it (squared, over the edge's length; default 0: none). More "
                  "slides boundary vertices onto headlands and the heads of inlets, at the cost "
                  "of angles")
      ->check(kNonNegative)
      ->group("Quads");
  cmd->add_option("--output-format", m.output_formats,
                  "gpkg, vtu, vtk, msh, gr3, nc, 2dm, mesh, pli, slf, 14, geojson or fgb: once for "
                  "every -o, "
                  "or once per "
                  "-o in order "
                  "(default: by extension)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"gpkg", "vtu", "vtk", "msh", "gr3", "nc", "2dm", "mesh", "pli", "slf",
                             "14", "geojson", "fgb"}))
      ->group("Output");
  cmd->add_option("--msh-version", m.msh_version, "Gmsh file version: 4.1 (default) or 2.2")
      ->check(CLI::IsMember({"4.1", "2.2"}))
      ->group("Output");
  cmd->add_option("--msh-groups", m.msh_groups,
                  "Gmsh physical groups of the boundary: kind (default: land 1, open 2) or "
                  "segment (land 1, each open segment its own: open_1, open_2... tagged 11, "
                  "12..., in hgrid.gr3's order, for a boundary condition per open boundary)")
      ->check(CLI::IsMember({"kind", "segment"}))
      ->group("Output");
  cmd->add_option("--output-crs", m.output_crs,
                  "Write coordinates in this CRS (e.g. EPSG:4326); SCHISM .gr3 stays in the "
                  "meshing CRS (its .ll is in lon/lat)")
      ->group("Output");
  cmd->add_option("--numbering", m.numbering,
                  "rcm (default): nodes in reverse Cuthill-McKee order, neighbours numbered close "
                  "together (a small bandwidth, as OceanMesh2D's renum and SMS's renumbering "
                  "give an ADCIRC grid), and quads after their nodes; tiles: as the subdivision "
                  "numbers them (tile corners, then sides' midpoints, then centres)")
      ->check(CLI::IsMember({"rcm", "tiles"}))
      ->group("Output");
  cmd->add_flag("--schism-split", m.schism_split,
                "In SCHISM's .gr3 and .ll, each quad that fails SCHISM's checks (smallest over "
                "largest angle under 0.5, or longest over shortest side over 5) as two "
                "triangles, as SCHISM's manual asks (its "
                "fix_bad_quads); the other outputs keep every quad")
      ->group("Output");
  cmd->add_flag("--depth-average", m.depth_average,
                "Each vertex's depth as the mean of the raster's cells within a square as wide "
                "as the mean side of its quads (OceanMesh2D's cell averaging: no aliasing of a "
                "grid much finer than the mesh), where the raster has two or more cells across "
                "it (a mesh's nodes or soundings: four or more in it); its bilinear value "
                "elsewhere")
      ->group("Output");
  cmd->add_option(
         "--zones", m.zones.path,
         "Vector file (any format, with a CRS) of polygons whose attribute --zones-field "
         "numbers them (1 or more): each quad takes the number of the first that holds "
         "its centroid (0: none), as a .2dm's material, SCHISM's hgrid.prop beside a .gr3, "
         "a .msh's physical group (zone_N), a .slf's FRIC_ID (each node's: that of most of its "
         "quads) and a cell value of .gpkg, .geojson, .fgb, .vtu, .vtk and .nc (friction or "
         "vegetation classes, a model's regions)")
      ->group("Output");
  cmd->add_option("--zones-field", m.zones.field,
                  "Attribute of --zones holding the numbers (default: zone)")
      ->group("Output");
  cmd->add_option("--zones-layer", m.zones.layer, "Layer of --zones to read (default: its first)")
      ->group("Output");
}

void finish_front_end_args(CommonArgs& a) {
  if (a.outputs.empty() && !a.output_optional)
    throw Error(ErrorClass::usage, "options", "give the output with -o FILE");
  if (a.outputs.size() > 1 && !a.many_outputs)
    throw Error(ErrorClass::usage, "options", "this subcommand writes one output: give -o once");
  a.output = a.outputs.empty() ? "" : a.outputs.front();
  a.fe.read.path = a.input;
  if (!a.fe.open_boundary_layer.empty() && a.fe.open_boundary_path.empty())
    throw Error(ErrorClass::usage, "options", "--open-boundary-layer needs --open-boundary");
  if (!a.bbox.empty()) a.fe.read.bbox = parse_bbox(a.bbox);
  if (a.bbox.empty() && !a.fe.read.bbox_crs.empty() && a.fe.clip_path.empty())
    throw Error(ErrorClass::usage, "options", "--bbox-crs is the CRS of --bbox: give --bbox");
  a.fe.kind = a.domain_kind == "water" ? DomainKind::water
              : a.domain_kind == "sea" ? DomainKind::sea
                                       : DomainKind::land;
  a.fe.kind_given = !a.domain_kind.empty();
  if (a.simplify_m >= 0) a.fe.simplify_m = a.simplify_m;
  if (a.min_island_area_m2 >= 0) a.fe.min_island_area_m2 = a.min_island_area_m2;
  if (a.min_width_m >= 0) a.fe.min_width_m = a.min_width_m;
  if (a.hairline_m >= 0) a.fe.hairline_m = a.hairline_m;
}

FieldsOptions fields_options(const CommonArgs& a, const FieldArgs& f) {
  FieldsOptions o;
  o.front = a.fe;
  o.sizing = f.sizing;
  if (!o.sizing.size_mesh_path.empty()) {
    mesh_file_format(o.sizing.size_mesh_path);  // a mesh format, or a usage error
    o.sizing.size_mesh_crs = a.fe.read.src_crs;
  }
  if (a.fe.target_size_m > 0) o.sizing.constant_m = a.fe.target_size_m;
  // Every source is clamped to [hmin, hmax]: a --size outside would be a bound's value.
  if (o.sizing.constant_m && o.sizing.hmin_m > 0 && *o.sizing.constant_m < o.sizing.hmin_m)
    throw Error(ErrorClass::usage, "options",
                printf_string("--size %g is under --hmin %g, which every size is raised to",
                              *o.sizing.constant_m, o.sizing.hmin_m));
  if (o.sizing.constant_m && o.sizing.hmax_m > 0 && *o.sizing.constant_m > o.sizing.hmax_m)
    throw Error(ErrorClass::usage, "options",
                printf_string("--size %g is over --hmax %g, which every size is lowered to",
                              *o.sizing.constant_m, o.sizing.hmax_m));
  if (f.min_depth_m) o.sizing.min_depth_m = std::max(o.sizing.min_depth_m, *f.min_depth_m);
  o.sizing.automatic = f.size_auto || !has_explicit_source(o.sizing);
  if (!std::isnan(f.cross_angle_deg) && !f.cross_raster.empty())
    throw Error(ErrorClass::usage, "options", "give --cross-angle or --cross-raster, not both");
  if (!std::isnan(f.cross_angle_deg)) {
    o.cross.source = CrossSource::constant;
    o.cross.angle_deg = f.cross_angle_deg;
  } else if (!f.cross_raster.empty()) {
    o.cross.source = CrossSource::raster;
    o.cross.raster_path = f.cross_raster;
  }
  o.cross.conformal = f.cross_conformal;
  if (!f.sizing.refine_width_field.empty() && f.sizing.refine_path.empty())
    throw Error(ErrorClass::usage, "options", "--refine-width-field needs --refine");
  if ((f.sizing.refine_field != SizingParams().refine_field || !f.sizing.refine_layer.empty()) &&
      f.sizing.refine_path.empty())
    throw Error(ErrorClass::usage, "options", "--refine-field and --refine-layer need --refine");
  if (!f.align_layer.empty() && f.align_path.empty())
    throw Error(ErrorClass::usage, "options", "--align-layer needs --align");
  if (!f.align_path.empty() && o.cross.source == CrossSource::constant)
    throw Error(ErrorClass::usage, "options",
                "--align shapes the boundary-aligned cross field: not with --cross-angle");
  o.front.align_path = f.align_path;
  o.front.align_layer = f.align_layer;
  o.background_factor = f.background_factor;
  o.max_quads = f.max_quads;
  return o;
}

// The depth rasters can be read, and the options that need depths have them; a mesh
// among them without a CRS of its own is in --src-crs, when given.
void finish_depth_options(const CommonArgs& a, FieldArgs& f) {
  if (!f.depth_crs.empty()) parse_crs(f.depth_crs, "--depth-crs");
  for (DepthRaster& r : f.sizing.bathymetry) {
    r.crs_if_none = f.depth_crs.empty() ? a.fe.read.src_crs : f.depth_crs;
    r.field = f.depth_field;
    check_depth_source(r);
  }
  // (An .xyz has only x, y and the value: no attribute to name.)
  if (!f.depth_field.empty() && std::none_of(f.sizing.bathymetry.begin(), f.sizing.bathymetry.end(),
                                             [](const DepthRaster& r) {
                                               return is_sample_file(r.path) &&
                                                      !ends_with(lower_case(r.path), ".xyz");
                                             }))
    throw Error(ErrorClass::usage, "options",
                "--depth-field names the attribute of a layer of points given as --bathymetry "
                "or --elevation; none is (an .xyz holds x, y and the value only, a raster or "
                "mesh its own values)");
  if (!f.sizing.bathymetry.empty()) return;
  auto needs = [](const char* option) {
    throw Error(ErrorClass::usage, "options",
                std::string(option) + " needs depths: --bathymetry or --elevation");
  };
  if (f.min_depth_m) needs("--min-depth");
  if (!f.depth_crs.empty()) needs("--depth-crs");
  if (f.sizing.wavelength_period_s > 0) needs("--wavelength-period");
  if (f.sizing.cells_per_wavelength > 0) needs("--cells-per-wavelength");
  if (f.sizing.slope_factor > 0) needs("--slope-factor");
  if (f.sizing.time_step_s > 0) needs("--time-step");
  if (f.sizing.courant != SizingParams().courant) needs("--courant");
}

std::vector<MeshOutput> mesh_outputs(const CommonArgs& a, const MeshArgs& m) {
  const auto& formats = m.output_formats;
  if (formats.size() > 1 && formats.size() != a.outputs.size())
    throw Error(ErrorClass::usage, "options",
                "give --output-format once, or once per -o (" + std::to_string(a.outputs.size()) +
                    " outputs, " + std::to_string(formats.size()) + " formats)");
  std::vector<MeshOutput> outs;
  for (std::size_t i = 0; i < a.outputs.size(); ++i) {
    MeshOutput o;
    o.path = a.outputs[i];
    o.format = formats.empty() ? "" : formats.size() == 1 ? formats[0] : formats[i];
    o.overwrite = a.overwrite;
    o.zones = m.zones.given();
    outs.push_back(o);
  }
  return outs;
}

MeshOptions mesh_options(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m) {
  MeshOptions options = m.mesh;
  options.fields = fields_options(a, f);
  if (options.embed_lines && f.align_path.empty())
    throw Error(ErrorClass::usage, "options", "--embed needs --align: the lines to embed");
  if (!m.zones.given() && (!m.zones.layer.empty() || m.zones.field != ZonesSource().field))
    throw Error(ErrorClass::usage, "options", "--zones-field and --zones-layer need --zones");
  options.fields.front.embed_points_path = m.embed_points;
  options.fields.front.embed_points_name_field = m.embed_points_name;
  if (!m.embed_points_name.empty() && m.embed_points.empty())
    throw Error(ErrorClass::usage, "options",
                "--embed-points-name names an attribute of --embed-points' file: give the file");
  options.subdivide.corner_angle_deg = options.tiling.graph.corner_angle_deg;
  options.tiling.conform_rule =
      m.conform_rule == "longest-away"      ? ConformShiftRule::longest_away_from_corner
      : m.conform_rule == "longest-towards" ? ConformShiftRule::longest_towards_corner
      : m.conform_rule == "lattice"         ? ConformShiftRule::lattice
                                            : ConformShiftRule::close_shortest;
  options.tiling.init = m.init == "merge" ? TilingInit::merge : TilingInit::front;
  options.renumber = m.numbering == "rcm";
  options.tiling.stop_after = m.stop_after == "init"        ? TilingStep::init
                              : m.stop_after == "relax"     ? TilingStep::relax
                              : m.stop_after == "conform"   ? TilingStep::conform
                              : m.stop_after == "butterfly" ? TilingStep::butterfly
                              : m.stop_after == "resplit"   ? TilingStep::resplit
                                                            : TilingStep::none;
  return options;
}

MeshWriteOptions mesh_write_options(const MeshArgs& m) {
  MeshWriteOptions w;
  w.msh_version = m.msh_version;
  w.msh_groups = m.msh_groups;
  w.output_crs = m.output_crs;
  w.schism_split = m.schism_split;
  return w;
}

// --skip-existing: every file the run would write exists.
bool every_output_exists(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m) {
  std::error_code ec;
  for (const MeshOutput& o : mesh_outputs(a, m))
    if (!mesh_output_exists(o)) return false;
  for (const std::string& p : {a.report_path, f.plot_path})
    if (!p.empty() && p != kStdoutPath && !std::filesystem::exists(p, ec)) return false;
  return true;
}

void check_not_partly_written(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m) {
  std::error_code ec;
  std::vector<std::string> present, missing;
  auto sort_out = [&](const std::string& path) {
    (std::filesystem::exists(path, ec) ? present : missing).push_back(path);
  };
  for (const MeshOutput& o : mesh_outputs(a, m)) {
    if (mesh_output_exists(o)) {  // a .pli's numbered files among them
      present.push_back(o.path);
      continue;
    }
    for (const std::string& path : mesh_output_files(o)) sort_out(path);
  }
  for (const std::string& p : {a.report_path, f.plot_path})
    if (!p.empty() && p != kStdoutPath) sort_out(p);
  if (present.empty() || missing.empty()) return;
  throw Error(
      ErrorClass::usage, "options",
      "--skip-existing: '" + present[0] + "' exists" +
          (present.size() > 1 ? " (and " + std::to_string(present.size() - 1) + " more)" : "") +
          " but not '" + missing[0] + "'" +
          (missing.size() > 1 ? " (and " + std::to_string(missing.size() - 1) + " more)" : "") +
          ": a run stopped part-way leaves none of its outputs, so these are another "
          "run's; remove them to mesh again");
}

}  // namespace isoquad::cli
