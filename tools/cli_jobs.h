// The isoquad subcommands' jobs on their parsed arguments (cli_args.h): each checks its
// outputs before any work, runs the library's job, writes its outputs together and prints
// its summary. Failures are Error, which main maps to exit codes.
#pragma once

#include <string>
#include <vector>

#include "app/each_job.h"
#include "cli_args.h"

namespace isoquad::cli {

// Clears an unfinished progress line, so that an error or warning starts its own line.
void end_progress_line();

// The command line as the outputs record it (a GeoPackage's metadata, a netCDF's history,
// the report): the program as `isoquad`, each argument quoted for a POSIX shell where it
// needs to be, and without the options that change no output (--jobs, --overwrite,
// --skip-existing, -q, --each-table), so that a batch on one thread or two, resumed, or
// run again with --overwrite writes the same bytes.
std::string joined_command_line(int argc, char** argv);

// --skip-existing, every output there: what they record of the run that wrote them,
// against `command_line` (joined_command_line()). Warnings (without "isoquad: warning: ")
// for the report, GeoPackage and netCDF outputs that do not read as isoquad's, and when
// they record another command, naming the options that differ (command_difference(); with
// --each, --where is not compared, nor --clip-where with --each-clip: a region is its
// value's features, recorded by their ids); none when they record this one (in any
// order), or none. `unreadable`, when given: the files that do not read as isoquad's.
std::vector<std::string> skipped_outputs_warnings(const CommonArgs& a, const MeshArgs& m,
                                                  const std::string& command_line,
                                                  std::vector<std::string>* unreadable = nullptr);

// isoquad domain: the planar domain and its summary.
int run_domain(CommonArgs& a);
// isoquad fields: the background mesh with its sizes and crosses.
int run_fields(CommonArgs& a, FieldArgs& f, const std::string& command_line);
// The mesh job; with --each, one region's (printing into `console`).
RegionOutcome run_mesh(CommonArgs& a, FieldArgs& f, MeshArgs& m, const std::string& command_line,
                       const Console& console = Console());
// A mesh from a file measured against the domain's fields; -o and --plot as the mesh
// job's, for a mesh of quads alone.
RegionOutcome run_quality(CommonArgs& a, FieldArgs& f, const QualityArgs& q,
                          const std::string& command_line, const Console& console = Console());

}  // namespace isoquad::cli
