// --each and --each-clip on the command line (cli_each.h).
#include "cli_each.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "app/each_job.h"
#include "app/front_end.h"
#include "app/quality_report.h"
#include "cli_jobs.h"
#include "core/error.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/gdal_env.h"
#include "gis/raster_domain.h"
#include "gis/read_mesh.h"
#include "gis/read_polygons.h"
#include "io/write_mesh.h"

namespace isoquad::cli {

namespace {

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

// The folders of `path` (a template with {}) that the region's file name names, from the
// first with {} down (runs/{}/hgrid.gr3: runs/Malta), noted as folders the batch may make.
void note_region_directories(const std::string& path, const std::string& name) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::filesystem::path filled;
  bool marked = false;
  for (const std::filesystem::path& part : folder) {
    marked = marked || has_each_mark(part.string());
    filled /= fill_each_mark(part.string(), name);
    if (marked) note_creatable_directory(filled.string());
  }
}

// A region per selected value: {} in the paths replaced by its file name.
std::vector<EachRegion> regions_of(const CommonArgs& a, const FieldArgs& f,
                                   const std::string& field,
                                   const std::vector<SelectionValue>& selected, bool over_clip) {
  std::vector<std::string> values;
  std::vector<bool> null;
  // Text that is not UTF-8 (a .dbf without its .cpg) read as Windows-1252, for the
  // console, the table, the reports and the file names.
  for (const SelectionValue& v : selected) {
    values.push_back(utf8_or_cp1252(v.text));
    null.push_back(v.null);
  }
  // The features without a value: their file name that of an empty value, "_".
  const std::vector<std::string> names =
      each_file_names(field, values, null, over_clip ? "--each-clip" : "--each");
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
    for (std::string* path : {&r.a.report_path, &r.f.plot_path}) {
      note_region_directories(*path, names[k]);
      *path = fill_each_mark(*path, names[k]);
    }
    for (std::string& o : r.a.outputs) {
      note_region_directories(o, names[k]);
      o = fill_each_mark(o, names[k]);
    }
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
  // Each region's area is one polygon (read_clip_area): values that several polygons
  // share fail here, all named, rather than region by region.
  std::vector<std::string> shared;
  for (const SelectionValue& v : selected)
    if (v.num_features > 1 || v.num_polygons > 1)
      shared.push_back((v.null ? std::string("NULL") : "'" + utf8_or_cp1252(v.text) + "'") + " (" +
                       (v.num_features > 1
                            ? std::to_string(v.num_features) + " polygons"
                            : "a multi-polygon of " + std::to_string(v.num_polygons) + " parts") +
                       ")");
  if (!shared.empty()) {
    std::string list;
    for (std::size_t k = 0; k < shared.size() && k < 5; ++k) list += (k ? ", " : "") + shared[k];
    if (shared.size() > 5) list += " and " + std::to_string(shared.size() - 5) + " more";
    throw Error(ErrorClass::input, "read",
                "--clip '" + clip.path + "': --each-clip " + field +
                    " meshes one polygon per value, and several polygons have the value " + list +
                    ": give each its own value, merge them into one, or run over an attribute "
                    "that tells them apart (--each-clip fid; a multi-polygon's parts split into "
                    "features first, as ogr2ogr -explodecollections does)");
  }
  std::vector<EachRegion> regions = regions_of(a, f, field, selected, true);
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
  std::vector<EachRegion> regions = regions_of(a, f, field, selected, false);
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

}  // namespace

// checked before any meshing.
int run_mesh_each(const CommonArgs& a, const FieldArgs& f, const MeshArgs& m,
                  const std::string& command_line) {
  if (!m.stop_after.empty())
    throw Error(ErrorClass::usage, "options", "--each meshes: no --stop-after");
  const VectorDatasetPool pool;  // INPUT and the other vector files read once, not per region
  const CreatableDirectories region_folders;  // -o runs/{}/hgrid.gr3
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
  return run_each(
      table_args, over_clip ? "--each-clip" : "--each", field, regions, m.jobs, "meshed",
      m.each_table, [&](EachRegion& r, const Console& console) {
        // The region's features recorded by their ids too: another --where that gives the
        // value other features makes another region.
        const std::string region_command_line =
            command_line + (over_clip ? " [--each-clip: " : " [--each: ") + r.filter +
            (r.id_filter != r.filter ? " (" + r.id_filter + ")" : "") + "]";
        std::vector<std::string> unreadable;  // files warned of as not isoquad's
        if (r.skip) {
          if (!a.quiet) {
            console.out << "skipped: every output exists (--skip-existing)\n";
            for (const std::string& w :
                 skipped_outputs_warnings(r.a, m, region_command_line, &unreadable))
              console.err << "isoquad: warning: " << w << "\n";
          }
          const bool report_unreadable =
              std::find(unreadable.begin(), unreadable.end(), r.a.report_path) != unreadable.end();
          RegionOutcome outcome;
          outcome.skipped = true;
          // The table's figures from the region's report, when it has one.
          if (!r.a.report_path.empty() && r.a.report_path != "-") {
            outcome.quality = read_report_quality(r.a.report_path);
            if (!outcome.quality && !a.quiet && !report_unreadable)
              console.err << "isoquad: warning: '" << r.a.report_path
                          << "' does not read as an isoquad mesh report (damaged, cut short, or "
                             "another program's): the table has no figures for the region\n";
          }
          return outcome;
        }
        MeshArgs mm = m;
        try {
          return run_mesh(r.a, r.f, mm, region_command_line, console);
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
          if (earlier.size() > 3) list += " and " + std::to_string(earlier.size() - 3) + " more";
          throw Error(e.error_class(), e.stage(),
                      e.message() + "; its files of an earlier run stay as they were (" + list +
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
  const CreatableDirectories region_folders;  // -o out/{}/quality.gpkg
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

}  // namespace isoquad::cli
