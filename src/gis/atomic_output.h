// Outputs are written to a temporary file next to the destination and renamed into
// place only when complete, so a failure never leaves a partial output behind.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace isoquad {

// Fails early (Error(output)) when `path` exists and `overwrite` is false, or when its
// directory does not exist or is not writable. Call before any long work.
void check_output_path(const std::string& path, bool overwrite);

// While one lives (the command line's run), the files the run reads are its inputs, and
// no output may replace or remove one, even with overwrite: check_output_path, and the
// moves into place (AtomicOutput::commit, OutputSet::commit_all), fail with
// Error(output) naming it. A mesh written over its INPUT with --overwrite, or a --report
// over --mesh's file, would otherwise lose the input once the run succeeds. Without
// one (tests, the library's callers), nothing is noted.
class ProtectInputFiles {
 public:
  ProtectInputFiles();
  ~ProtectInputFiles();
  ProtectInputFiles(const ProtectInputFiles&) = delete;
  ProtectInputFiles& operator=(const ProtectInputFiles&) = delete;
};

// Notes `path` as an input of the run (under ProtectInputFiles; the readers call it as
// they open a file). A name that is no regular file (a data source such as PG:..., a
// directory of shapefiles) is not noted. Thread-safe.
void note_input_file(const std::string& path);

// While one lives (a batch's run), the directories noted with note_creatable_directory
// may be missing: check_output_path takes a path in one when the nearest directory that
// exists above it is writable, and an AtomicOutput makes them as it starts writing. A
// batch's per-region folders (-o runs/{}/hgrid.gr3) cannot be made beforehand by a user
// who does not know the regions' file names; a region that fails makes none.
class CreatableDirectories {
 public:
  CreatableDirectories();
  ~CreatableDirectories();
  CreatableDirectories(const CreatableDirectories&) = delete;
  CreatableDirectories& operator=(const CreatableDirectories&) = delete;
};

// Notes `dir` as a directory the run may make (under CreatableDirectories). Thread-safe.
void note_creatable_directory(const std::string& dir);

// The path as one file's key, so that two spellings of one file compare equal (./a and
// a, a link to its directory): canonical as far as it exists, else absolute and
// normalised (a name too long to look up).
std::string output_path_key(const std::string& path);

// Removes the temporary files of the outputs still being written when the process is
// stopped by SIGINT, SIGTERM or SIGHUP, then lets the signal end it as it would have
// (exit status 128 + the signal's number in a shell). Call first thing in main, before
// any thread starts: it blocks those signals in the calling thread (the threads started
// later inherit that) and waits for them on a thread of its own. A signal that comes
// while an OutputSet moves its outputs into place waits until every one is moved.
void remove_unfinished_outputs_on_signals();

// Removes the temporary files of every AtomicOutput alive and not committed, with their
// SQLite side files (what the signal handling above does; for tests).
void remove_unfinished_outputs();

// Writes `text` to `path` through an AtomicOutput. Throws Error(output).
void write_text_file(const std::string& path, const std::string& text, bool overwrite);

class AtomicOutput {
 public:
  AtomicOutput(std::string final_path, bool overwrite);
  ~AtomicOutput();  // removes the temporary file unless committed
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  // Where the writer writes; it keeps the destination's extension.
  const std::string& temp_path() const { return temp_path_; }
  const std::string& final_path() const { return final_path_; }
  // Moves the finished temporary file into place. Throws Error(output).
  void commit();

 private:
  std::string final_path_;
  std::string temp_path_;
  bool overwrite_ = false;
  bool committed_ = false;
};

// Several outputs written as one: each goes to its temporary file, and only when all are
// complete are they moved into place. If a move fails, the outputs already moved are
// removed again and the files they replaced (with overwrite) are put back, so a run
// leaves either every new output or the files as they were.
// The paths of an OutputSet checked before the work (check_output_path, and a path given
// twice), writing nothing and making no directory.
class OutputPathCheck {
 public:
  // Throws as OutputSet::add.
  void add(const std::string& final_path, bool overwrite);

 private:
  std::vector<std::string> paths_;
};

class OutputSet {
 public:
  // Adds an output and returns where to write it. Throws Error(output) (see
  // check_output_path) or Error(usage) for a path given twice.
  const std::string& add(const std::string& final_path, bool overwrite);
  // A file of an earlier run that the outputs replace without writing it again (a .pli
  // output's numbered file for a segment the new mesh does not have): removed when they
  // are moved into place, kept when they are not.
  void remove_on_commit(const std::string& path);
  // Moves every output into place, or none. Throws Error(output).
  void commit_all();
  std::size_t size() const { return outputs_.size(); }
  // A writer's error as the user should read it: the temporary files named by the
  // outputs' names, and a disk with under 1 MB free said (a writer's own message seldom
  // tells why it failed).
  Error explained(const Error& e) const;

 private:
  std::vector<std::string> removed_;
  std::vector<std::string> paths_;
  std::vector<char> overwrite_;
  std::vector<std::unique_ptr<AtomicOutput>> outputs_;
};

}  // namespace isoquad
