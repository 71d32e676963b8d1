// The command line a run records in its outputs (the report's "command_line", a
// GeoPackage's metadata, a netCDF file's history), read back and compared with another:
// what --skip-existing says of outputs that another command wrote.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/write_mesh.h"

namespace isoquad {

// `arg` as a POSIX shell reads it back: as it is when it holds only letters, digits and
// -_./,:=+@%, else in single quotes (a quote inside as '\'').
std::string shell_quoted(const std::string& arg);

// A command line joined of shell_quoted() arguments, split into its arguments again.
std::vector<std::string> shell_words(const std::string& line);

// A command-line option as the comparison reads it.
struct OptionShape {
  std::string name;  // its first name, for all its names ("--output" for -o)
  int values = 1;    // how many values it takes (0: a flag)
};

// An output's record of the command that wrote it.
struct RecordedCommand {
  std::string file;     // the file it was read from
  std::string command;  // as the run recorded it (joined, each argument shell-quoted)
};

// The record in the report at `report_path` (unless empty or "-"), else in the first
// GeoPackage output among `meshes`, else the first netCDF one; nullopt when none holds
// one (the other formats keep none that is read back). A file that is not one of
// isoquad's, or is damaged, holds none: with `unreadable`, those of them that exist are
// added to it (all of them, also after the record is found).
std::optional<RecordedCommand> recorded_command(const std::vector<MeshOutput>& meshes,
                                                const std::string& report_path,
                                                std::vector<std::string>* unreadable = nullptr);

// How the command `recorded` differs from `current` (both as recorded), as a clause such
// as "it had --hmax 5000 where this command has --hmax 4000; this command adds --repair";
// empty when they give the same options. Compared as sets of options with their
// values, so that the options' order, --opt=value against --opt value, and numbers
// written differently (5000, 5e3, 5000.0) do not count; `ignored` options (with their
// values) are left out of the comparison. A region's selection, recorded after the
// command as " [--each: FILTER]", is compared as a whole.
// `options`: each option's shape by each of its names ("-o" and "--output"); an option
// not in it takes every word up to the next option. `ignored` by their first names.
std::string command_difference(const std::string& recorded, const std::string& current,
                               const std::map<std::string, OptionShape>& options,
                               const std::vector<std::string>& ignored = {});

}  // namespace isoquad
