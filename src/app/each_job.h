// `isoquad mesh --each FIELD`: a mesh per value of an attribute. The regions' file names,
// their runs on one or more threads with what each prints kept in the regions' order,
// and the table that ends the batch. What a region's run is, the caller says.
#pragma once

#include <cstddef>
#include <functional>
#include <iostream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "quad/quad_quality.h"

namespace isoquad {

// What stands for the region's value in the output paths (-o out/{}.gpkg).
inline constexpr const char* kEachMark = "{}";

bool has_each_mark(const std::string& path);
// `path` with every {} replaced by `name`.
std::string fill_each_mark(std::string path, const std::string& name);

// The regions' values as file names: ASCII other than letters, digits, '.', '-' and '_'
// as '_' (UTF-8 kept, other bytes as '_'), "_" for an empty value, a leading '-' as '_'.
// Error(usage) naming both values when two give the same name, after `option` and
// `field`; a value whose `null` is true (the features without one) as NULL.
std::vector<std::string> each_file_names(const std::string& field,
                                         const std::vector<std::string>& values,
                                         const std::vector<bool>& null = {},
                                         const std::string& option = "--each");

// Where a job prints its summary and its warnings, and whether it shows progress
// (regions meshed at once print into buffers, without progress).
struct Console {
  std::ostream& out = std::cerr;
  std::ostream& err = std::cerr;
  bool progress = true;
};

// How a region's run ended.
struct RegionOutcome {
  std::optional<QualitySummary> quality;  // meshed
  double seconds = 0.0;
  bool skipped = false;  // nothing to do (--skip-existing)
  int exit = 0;          // failed: its exit code
  std::string error;     // failed: the message, as the error gave it
  // Failed on the command (a usage error, exit 2): the message, as the error gave it.
  std::string usage_error;
  bool not_run = false;  // the batch stopped before it (see run_regions)
};

// Runs `run(k, console)` for the regions k = 0 .. n-1 on `jobs` threads. Each region's
// `header(k)` and what it prints reach `stream` in the regions' order: with one thread as
// it goes, with more from buffers, each region's as soon as it and those before it are
// done (its out, then its err). Once two regions have failed with the same usage error
// (one that names no place of theirs: the command is wrong for every region), no other
// region starts: those are `not_run`, and so are those after the second in order that
// several threads had started and that failed with such an error or were skipped
// (neither printed), so
// that the outcomes are one thread's. Anything `run` throws is rethrown once every
// started region has run. `finished`, when given, is called with the outcomes so far
// (those not yet ended `not_run`) each time a region ends, one call at a time; it must
// not throw.
std::vector<RegionOutcome> run_regions(
    std::size_t n, std::size_t jobs, const std::function<std::string(std::size_t)>& header,
    const std::function<RegionOutcome(std::size_t, const Console&)>& run,
    std::ostream& stream = std::cerr,
    const std::function<void(const std::vector<RegionOutcome>&)>& finished = {});

// A line per region (its quads' quality and seconds, or skipped, or failed), under a
// header, the values padded to one width in characters (UTF-8).
std::string format_each_table(const std::string& field, const std::vector<std::string>& values,
                              const std::vector<RegionOutcome>& outcomes);
// "--each FIELD: M of N meshed[, S skipped (every output exists)][; failed: a, b]" (`done`
// for "meshed", `option` for "--each"), and when the batch stopped, how many were not run
// and why.
std::string format_each_total(const std::string& field, const std::vector<std::string>& values,
                              const std::vector<RegionOutcome>& outcomes,
                              const std::string& done = "meshed",
                              const std::string& option = "--each");
// A region as the CSV names it: its value (an empty field for the features without one)
// and its file name, what {} stands for in its paths.
struct EachCsvRegion {
  std::string value, file;
  bool null = false;
};
// The table as CSV (--each-table), for a batch's records and golden files: a header, then
// a row per region in the regions' order: its value, file name, status (`done`, failed,
// skipped, not run), exit code (empty for one not run), quads, vertices, the quality
// figures (shares in percent) and the error of a failed one. No seconds: the same batch
// gives the same bytes.
std::string format_each_csv(const std::string& field, const std::vector<EachCsvRegion>& regions,
                            const std::vector<RegionOutcome>& outcomes,
                            const std::string& done = "meshed");
// The CSV's column types for GDAL and QGIS (a .csvt beside a .csv: without it every
// column reads as text), and that file's path: the table's with .csvt for a .csv, else
// empty (no such file).
std::string format_each_csv_types();
std::string each_csv_types_path(const std::string& table_path);
// The first failed region's exit code, 0 when none failed.
int each_exit_code(const std::vector<RegionOutcome>& outcomes);

}  // namespace isoquad
