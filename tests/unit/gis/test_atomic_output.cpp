#include "gis/atomic_output.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <functional>

#include "core/error.h"
#include "support/test_support.h"

using namespace isoquad;
using namespace isoquad::test;

TEST(AtomicOutput, CommitMovesTheFileIntoPlace) {
  TempDir dir;
  const std::string path = dir.file("out.gpkg");
  {
    AtomicOutput out(path, false);
    EXPECT_NE(out.temp_path(), path);
    EXPECT_EQ(std::filesystem::path(out.temp_path()).extension(), ".gpkg");
    write_file(out.temp_path(), "data");
    out.commit();
  }
  EXPECT_EQ(read_file(path), "data");
  EXPECT_EQ(dir.entries().size(), 1u);
}

TEST(AtomicOutput, AFailureLeavesNothingBehind) {
  TempDir dir;
  const std::string path = dir.file("out.gpkg");
  try {
    AtomicOutput out(path, false);
    write_file(out.temp_path(), "half");
    write_file(out.temp_path() + "-journal", "journal");
    throw std::runtime_error("writer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicOutput, ExistingOutputNeedsOverwrite) {
  TempDir dir;
  const std::string path = dir.file("out.gpkg");
  write_file(path, "old");
  try {
    AtomicOutput out(path, false);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::output);
    EXPECT_NE(std::string(e.what()).find("already exists"), std::string::npos);
  }
  AtomicOutput out(path, true);
  write_file(out.temp_path(), "new");
  out.commit();
  EXPECT_EQ(read_file(path), "new");
}

// Under ProtectInputFiles, a file noted as read is never replaced nor removed, by
// another spelling of it too: not when checked, not when moved into place (an input read
// after the outputs were checked), not as a file an OutputSet removes. Without it, or
// once it ends, nothing is noted.
TEST(AtomicOutput, TheRunsInputsAreNeverReplaced) {
  TempDir dir;
  const std::string input = dir.file("in.geojson"), other = dir.file("other.gpkg");
  write_file(input, "input");
  auto expect_refused = [&](const std::function<void()>& f) {
    try {
      f();
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.error_class(), ErrorClass::output);
      EXPECT_NE(std::string(e.what()).find("is an input of this run"), std::string::npos)
          << e.what();
    }
    EXPECT_EQ(read_file(input), "input");
  };
  note_input_file(input);  // no ProtectInputFiles: not noted
  check_output_path(input, true);
  {
    const ProtectInputFiles protect;
    check_output_path(input, true);  // not read yet
    AtomicOutput late(input, true);  // checked before the file was read
    write_file(late.temp_path(), "output");
    note_input_file(input);
    note_input_file("PG:dbname=coast");  // a data source: nothing to note
    expect_refused([&] { check_output_path(input, true); });
    expect_refused([&] { check_output_path(dir.path() + "/./in.geojson", true); });
    expect_refused([&] { late.commit(); });
    OutputSet set;
    write_file(set.add(other, false), "other");
    set.remove_on_commit(input);
    expect_refused([&] { set.commit_all(); });
    EXPECT_FALSE(std::filesystem::exists(other));
  }
  check_output_path(input, true);  // the run is over
}

TEST(AtomicOutput, MissingDirectoryIsAnOutputError) {
  TempDir dir;
  try {
    check_output_path(dir.file("no/such/dir/out.gpkg"), false);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.error_class(), ErrorClass::output);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

// A batch's region folders (CreatableDirectories): a path in a noted missing folder
// passes the checks, which make nothing; writing it makes the folder. Folders not noted,
// or noted outside the scope, stay errors.
TEST(AtomicOutput, NotedFoldersAreMadeWhenWritten) {
  TempDir dir;
  const std::string out = dir.file("runs/malta/grid/hgrid.gr3");
  {
    const CreatableDirectories scope;
    note_creatable_directory(dir.file("runs/malta"));
    note_creatable_directory(dir.file("runs/malta/grid/"));
    EXPECT_THROW(check_output_path(out, false), Error);  // runs is the user's to make
    std::filesystem::create_directory(dir.file("runs"));
    check_output_path(out, false);
    OutputPathCheck probe;
    probe.add(out, false);
    EXPECT_THROW(probe.add(dir.file("runs/./malta/grid/hgrid.gr3"), false), Error);
    EXPECT_FALSE(std::filesystem::exists(dir.file("runs/malta")));
    EXPECT_THROW(check_output_path(dir.file("runs/gozo/hgrid.gr3"), false), Error);
    {
      OutputSet set;
      write_file(set.add(out, false), "grid");
      set.commit_all();
    }
    EXPECT_EQ(read_file(out), "grid");
  }
  note_creatable_directory(dir.file("runs/gozo"));  // no scope: not noted
  EXPECT_THROW(check_output_path(dir.file("runs/gozo/hgrid.gr3"), false), Error);
  {
    const CreatableDirectories scope;
    // An output not finished (a failure, a signal) leaves no folder it made, but those
    // that hold another output.
    note_creatable_directory(dir.file("runs/gozo"));
    note_creatable_directory(dir.file("runs/gozo/grid"));
    {
      OutputSet set;
      write_file(set.add(dir.file("runs/gozo/grid/hgrid.gr3"), false), "g");
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("runs/gozo")));
    {
      AtomicOutput kept(dir.file("runs/gozo/report.json"), false);
      write_file(kept.temp_path(), "{}");
      kept.commit();
      AtomicOutput stopped(dir.file("runs/gozo/grid/hgrid.gr3"), false);
      write_file(stopped.temp_path(), "g");
      remove_unfinished_outputs();  // as on SIGINT
      EXPECT_FALSE(std::filesystem::exists(dir.file("runs/gozo/grid")));
      EXPECT_TRUE(std::filesystem::exists(dir.file("runs/gozo/report.json")));
    }
    // A folder name over the file system's limit, found by the check; a link to nothing
    // where the folder would be, named so.
    const std::string long_name(300, 'x');
    note_creatable_directory(dir.file("runs/" + long_name));
    try {
      check_output_path(dir.file("runs/" + long_name + "/m.gpkg"), false);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(
          std::string(e.what()).find("its folder '" + long_name + "' has 300 bytes, over the"),
          std::string::npos)
          << e.what();
    }
    std::filesystem::create_symlink(dir.file("nowhere"), dir.file("runs/link"));
    note_creatable_directory(dir.file("runs/link"));
    try {
      check_output_path(dir.file("runs/link/m.gpkg"), false);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("is a link to nothing"), std::string::npos) << e.what();
    }
  }
}

// When moving the second output into place fails, the first, already moved, is removed.
TEST(OutputSet, CommitIsAllOrNothing) {
  TempDir dir;
  {
    OutputSet set;
    write_file(set.add(dir.file("a.txt"), false), "a");
    write_file(set.add(dir.file("b.txt"), false), "b");
    write_file(dir.file("b.txt"), "someone else's");  // appears while writing
    EXPECT_THROW(set.commit_all(), Error);
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.txt")));
  EXPECT_EQ(read_file(dir.file("b.txt")), "someone else's");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"b.txt"});
  {
    OutputSet set;
    write_file(set.add(dir.file("a.txt"), false), "a");
    EXPECT_THROW(set.add(dir.path() + "/./a.txt", false), Error);  // the same file twice
    set.commit_all();
  }
  EXPECT_EQ(read_file(dir.file("a.txt")), "a");
}

// With overwrite, a failed move puts back the files the outputs had already replaced.
TEST(OutputSet, FailedCommitRestoresReplacedFiles) {
  TempDir dir;
  write_file(dir.file("a.txt"), "old a");
  {
    OutputSet set;
    write_file(set.add(dir.file("a.txt"), true), "new a");
    write_file(set.add(dir.file("b.txt"), true), "new b");
    // b.txt becomes a non-empty directory: the file cannot be moved over it.
    std::filesystem::create_directory(dir.file("b.txt"));
    write_file(dir.file("b.txt/x"), "x");
    EXPECT_THROW(set.commit_all(), Error);
  }
  EXPECT_EQ(read_file(dir.file("a.txt")), "old a");
  std::filesystem::remove_all(dir.file("b.txt"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.txt"});
  {
    OutputSet set;
    write_file(set.add(dir.file("a.txt"), true), "new a");
    write_file(set.add(dir.file("b.txt"), true), "new b");
    set.commit_all();
  }
  EXPECT_EQ(read_file(dir.file("a.txt")), "new a");
  EXPECT_EQ(read_file(dir.file("b.txt")), "new b");
  auto entries = dir.entries();
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"a.txt", "b.txt"}));  // no backup left
}

// What a signal leaves: the outputs still being written lose their temporary files (and
// their SQLite side files); a committed output stays.
TEST(AtomicOutput, UnfinishedOutputsAreRemovedOnRequest) {
  TempDir dir;
  {
    AtomicOutput done(dir.file("done.gpkg"), false);
    write_file(done.temp_path(), "done");
    done.commit();
    AtomicOutput half(dir.file("half.gpkg"), false);
    write_file(half.temp_path(), "half");
    write_file(half.temp_path() + "-journal", "journal");
    OutputSet set;
    write_file(set.add(dir.file("a.txt"), false), "a");
    EXPECT_EQ(dir.entries().size(), 4u);
    remove_unfinished_outputs();
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"done.gpkg"});
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"done.gpkg"});
  EXPECT_EQ(read_file(dir.file("done.gpkg")), "done");
}

// A process stopped by SIGTERM (or Ctrl-C's SIGINT) while writing removes its temporary
// files, keeps what it had committed, and still ends by the signal.
TEST(AtomicOutput, ASignalRemovesTheUnfinishedOutputsAndEndsTheProcess) {
  for (int sig : {SIGTERM, SIGINT}) {
    TempDir dir;
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      remove_unfinished_outputs_on_signals();
      AtomicOutput done(dir.file("done.txt"), false);
      write_file(done.temp_path(), "done");
      done.commit();
      OutputSet set;
      write_file(set.add(dir.file("a.gpkg"), false), "a");
      write_file(set.add(dir.file("b.msh"), false), "b");
      AtomicOutput nested(set.add(dir.file("c.gpkg"), false), false);
      write_file(nested.temp_path(), "c");
      write_file(nested.temp_path() + "-journal", "journal");
      kill(getpid(), sig);
      for (int i = 0; i < 500; ++i) usleep(10000);
      _exit(0);  // not stopped: the parent sees exit status 0
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"done.txt"});
    EXPECT_EQ(read_file(dir.file("done.txt")), "done");
  }
}

// A long output name (up to the file system's 255 bytes) keeps a short temporary name,
// also when a writer nests a second temporary file in the first (a GeoPackage's): a
// 240-byte name used to fail to open its temporary file. Names that differ only past the
// cut get different temporary names.
TEST(AtomicOutput, LongNamesGetShortTemporaryNames) {
  TempDir dir;
  const std::string stem(235, 'a'), other = std::string(234, 'a') + "b";
  const std::string path = dir.file(stem + ".gpkg");
  {
    AtomicOutput outer(path, false);
    AtomicOutput inner(outer.temp_path(), false);
    AtomicOutput sibling(dir.file(other + ".gpkg"), false);
    for (const AtomicOutput* o : {&outer, &inner, &sibling}) {
      const std::string name = std::filesystem::path(o->temp_path()).filename().string();
      EXPECT_LT(name.size(), 100u) << name;
      EXPECT_EQ(std::filesystem::path(name).extension(), ".gpkg");
    }
    EXPECT_NE(outer.temp_path(), sibling.temp_path());
    write_file(inner.temp_path(), "data");
    inner.commit();
    outer.commit();
  }
  EXPECT_EQ(read_file(path), "data");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{stem + ".gpkg"});
}

// Two outputs of one final path at once (two threads' regions) write to temporary files of
// their own: neither removes the other's, and the second to commit replaces the first.
TEST(AtomicOutput, TwoWritersOfOnePathGetTheirOwnTemporaryFiles) {
  TempDir dir;
  const std::string path = dir.file("out.gpkg");
  {
    AtomicOutput first(path, true);
    write_file(first.temp_path(), "first");
    AtomicOutput second(path, true);
    EXPECT_NE(second.temp_path(), first.temp_path());
    EXPECT_EQ(read_file(first.temp_path()), "first");
    write_file(second.temp_path(), "second");
    first.commit();
    second.commit();
  }
  EXPECT_EQ(read_file(path), "second");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.gpkg"});
}

// The keys of two spellings of one file are equal, and those of two names too long to
// look up differ.
TEST(AtomicOutput, PathKeysTellFilesApart) {
  TempDir dir;
  EXPECT_EQ(output_path_key(dir.file("a.gpkg")), output_path_key(dir.file("./x/../a.gpkg")));
  const std::string long_name(300, 'x');
  EXPECT_NE(output_path_key(dir.file(long_name + "a.gpkg")),
            output_path_key(dir.file(long_name + "b.gpkg")));
}

// A writer names the file it writes, the temporary one: the error the user reads names
// the output instead, and other errors pass as they were.
TEST(OutputSet, AWritersErrorNamesTheOutputNotItsTemporaryFile) {
  TempDir dir;
  OutputSet set;
  const std::string path = dir.file("mesh.vtu");
  const std::string temp = set.add(path, false);
  const std::string name = std::filesystem::path(temp).filename().string();
  const Error e =
      set.explained(Error(ErrorClass::output, "write",
                          "'" + temp + "': cannot write; sqlite3_open(" + name + ") failed"));
  EXPECT_EQ(e.error_class(), ErrorClass::output);
  EXPECT_EQ(e.stage(), "write");
  EXPECT_EQ(e.message().find(name), std::string::npos) << e.message();
  EXPECT_EQ(e.message().rfind("'" + path + "': cannot write; sqlite3_open(" + path + ") failed", 0),
            0u)
      << e.message();
  const Error other = set.explained(Error(ErrorClass::input, "read", "'" + temp + "'"));
  EXPECT_EQ(other.message(), "'" + temp + "'");
}
