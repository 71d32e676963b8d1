#include "gis/atomic_output.h"

#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <thread>
#include <utility>

#include "core/error.h"

namespace isoquad {

namespace fs = std::filesystem;

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

fs::path parent_dir(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

void remove_with_side_files(const std::string& path) {
  for (const char* suffix : {"", "-journal", "-wal", "-shm"}) std::remove((path + suffix).c_str());
}

// A file name's stem as the temporary file's name holds it: long ones cut (at a UTF-8
// character's start) and told apart by a hash of the whole, so that the temporary name
// stays well under the file system's 255 bytes however long the output's name is (a
// GeoPackage's writer nests a second temporary name in the first).
std::string short_stem(const std::string& stem) {
  constexpr std::size_t kKeep = 48;
  if (stem.size() <= 2 * kKeep) return stem;
  std::size_t cut = kKeep;
  while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xC0) == 0x80) --cut;
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016zx", std::hash<std::string>{}(stem));
  return stem.substr(0, cut) + "-" + hash;
}

// The temporary files of the outputs being written, for the signal handling. Its lock is
// held while an OutputSet moves its outputs into place. Never destroyed: a signal may
// come while the process exits.
struct UnfinishedOutputs {
  std::recursive_mutex mutex;
  std::vector<std::string> temp_paths;
};

UnfinishedOutputs& unfinished() {
  static UnfinishedOutputs* const registry = new UnfinishedOutputs;
  return *registry;
}

void forget_temp_path(const std::string& path) {
  UnfinishedOutputs& u = unfinished();
  std::lock_guard<std::recursive_mutex> lock(u.mutex);
  const auto it = std::find(u.temp_paths.begin(), u.temp_paths.end(), path);
  if (it != u.temp_paths.end()) u.temp_paths.erase(it);
}

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

// The run's inputs (ProtectInputFiles) by file identity, so that another spelling of
// one (./a, a link) is the same file.
struct InputFiles {
  std::mutex mutex;
  bool protect = false;
  std::set<std::pair<dev_t, ino_t>> ids;
};

InputFiles& input_files() {
  static InputFiles files;
  return files;
}

// The directories the run may make (CreatableDirectories), and those it made, absolute
// and normalised. Never destroyed: a signal may come while the process exits.
struct CreatableDirs {
  std::mutex mutex;
  bool active = false;
  std::set<std::string> dirs;
  std::set<std::string> made;
};

CreatableDirs& creatable_dirs() {
  static CreatableDirs* const dirs = new CreatableDirs;
  return *dirs;
}

std::string directory_key(const fs::path& dir) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(dir, ec);
  std::string key = (ec ? dir : absolute).lexically_normal().string();
  while (key.size() > 1 && key.back() == '/') key.pop_back();
  return key;
}

bool may_create(const fs::path& dir) {
  CreatableDirs& c = creatable_dirs();
  std::lock_guard<std::mutex> lock(c.mutex);
  return c.active && c.dirs.count(directory_key(dir)) > 0;
}

// Nothing at `d`, not even a link to nothing.
bool nothing_at(const fs::path& d) {
  std::error_code ec;
  const fs::file_type type = fs::symlink_status(d, ec).type();
  return type == fs::file_type::not_found || ec == std::errc::filename_too_long;
}

// The directory an output in `dir` needs to exist: `dir`, or the nearest one above it
// when the directories between may be made (`missing`: those, the deepest first).
fs::path existing_directory_for(const fs::path& dir, std::vector<fs::path>* missing = nullptr) {
  fs::path d = dir;
  while (nothing_at(d) && may_create(d)) {
    if (missing) missing->push_back(d);
    const fs::path up = d.parent_path();
    if (up.empty() || up == d) return fs::path(".");
    d = up;
  }
  return d;
}

// Removes the directories the run made that held `path`, from its own up, while they
// are empty (an output not finished: nothing of the region's left behind).
void remove_made_directories_above(const std::string& path) {
  CreatableDirs& c = creatable_dirs();
  std::lock_guard<std::mutex> lock(c.mutex);
  std::error_code ec;
  for (fs::path d = parent_dir(path); c.made.count(directory_key(d)) > 0; d = d.parent_path()) {
    if (!fs::remove(d, ec) || ec) return;  // not empty: another output is in it
    c.made.erase(directory_key(d));
  }
}

// Error(output) when `path` is an existing file the run reads.
void check_not_an_input(const std::string& path) {
  InputFiles& files = input_files();
  std::lock_guard<std::mutex> lock(files.mutex);
  struct stat st {};
  if (!files.protect || ::stat(path.c_str(), &st) != 0) return;
  if (files.ids.count({st.st_dev, st.st_ino}))
    throw Error(ErrorClass::output, "write",
                quote(path) +
                    " is an input of this run: isoquad never writes over its inputs, even with "
                    "--overwrite; give the output another name");
}

}  // namespace

ProtectInputFiles::ProtectInputFiles() {
  InputFiles& files = input_files();
  std::lock_guard<std::mutex> lock(files.mutex);
  files.protect = true;
}

ProtectInputFiles::~ProtectInputFiles() {
  InputFiles& files = input_files();
  std::lock_guard<std::mutex> lock(files.mutex);
  files.protect = false;
  files.ids.clear();
}

void note_input_file(const std::string& path) {
  InputFiles& files = input_files();
  std::lock_guard<std::mutex> lock(files.mutex);
  struct stat st {};
  if (!files.protect || ::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;
  files.ids.emplace(st.st_dev, st.st_ino);
}

CreatableDirectories::CreatableDirectories() {
  CreatableDirs& c = creatable_dirs();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.active = true;
}

CreatableDirectories::~CreatableDirectories() {
  CreatableDirs& c = creatable_dirs();
  std::lock_guard<std::mutex> lock(c.mutex);
  c.active = false;
  c.dirs.clear();
  c.made.clear();
}

void note_creatable_directory(const std::string& dir) {
  CreatableDirs& c = creatable_dirs();
  std::lock_guard<std::mutex> lock(c.mutex);
  if (c.active) c.dirs.insert(directory_key(dir));
}

void check_output_path(const std::string& path, bool overwrite) {
  if (path.empty()) throw Error(ErrorClass::usage, "write", "empty output path");
  check_not_an_input(path);
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw Error(ErrorClass::output, "write", quote(path) + " is a directory");
  if (fs::exists(path, ec) && !overwrite)
    throw Error(ErrorClass::output, "write",
                quote(path) + " already exists; pass --overwrite to replace it");
  std::vector<fs::path> missing;  // folders to make, the deepest first
  const fs::path dir = existing_directory_for(parent_dir(path), &missing);
  if (!fs::is_directory(dir, ec))
    throw Error(ErrorClass::output, "write",
                quote(path) + ": directory " + quote(dir.string()) +
                    (fs::exists(dir, ec)       ? " is a file"
                     : fs::is_symlink(dir, ec) ? " is a link to nothing"
                                               : " does not exist"));
  if (access(dir.c_str(), W_OK) != 0)
    throw Error(ErrorClass::output, "write",
                quote(path) + ": directory " + quote(dir.string()) + " is not writable");
  // A name longer than the file system takes would fail only at the end, after the work:
  // the file's, and those of the folders to make.
  const long name_max = pathconf(dir.c_str(), _PC_NAME_MAX);
  std::vector<std::string> names = {fs::path(path).filename().string()};
  for (const fs::path& m : missing) names.push_back(m.filename().string());
  for (std::size_t k = 0; k < names.size(); ++k)
    if (name_max > 0 && static_cast<long>(names[k].size()) > name_max)
      throw Error(ErrorClass::output, "write",
                  quote(path) + ": " + (k ? "its folder " + quote(names[k]) : "its name") +
                      " has " + std::to_string(names[k].size()) + " bytes, over the " +
                      std::to_string(name_max) + " the file system takes in a file name");
}

std::string output_path_key(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return (ec ? absolute.lexically_normal() : canonical).string();
}

AtomicOutput::AtomicOutput(std::string final_path, bool overwrite)
    : final_path_(std::move(final_path)), overwrite_(overwrite) {
  check_output_path(final_path_, overwrite_);
  // A batch's region folder (CreatableDirectories), made now that its output is written.
  std::error_code ec;
  if (!fs::is_directory(parent_dir(final_path_), ec)) {
    std::vector<fs::path> missing;
    existing_directory_for(parent_dir(final_path_), &missing);
    fs::create_directories(parent_dir(final_path_), ec);
    if (ec)
      throw Error(ErrorClass::output, "write",
                  quote(final_path_) + ": cannot make directory " +
                      quote(parent_dir(final_path_).string()) + ": " + ec.message());
    CreatableDirs& c = creatable_dirs();
    std::lock_guard<std::mutex> lock(c.mutex);
    for (const fs::path& m : missing) c.made.insert(directory_key(m));
  }
  const fs::path p(final_path_);
  const std::string stem = "." + short_stem(p.stem().string()) + ".tmp-" + std::to_string(getpid());
  UnfinishedOutputs& u = unfinished();
  std::lock_guard<std::recursive_mutex> lock(u.mutex);
  // Another output of this process being written to the same name (two threads, one
  // final path) gets a name of its own: neither removes the other's file.
  for (int n = 1;; ++n) {
    const fs::path name = stem + (n > 1 ? "-" + std::to_string(n) : "") + p.extension().string();
    temp_path_ = (parent_dir(final_path_) / name).string();
    if (std::find(u.temp_paths.begin(), u.temp_paths.end(), temp_path_) == u.temp_paths.end())
      break;
  }
  remove_with_side_files(temp_path_);
  u.temp_paths.push_back(temp_path_);
}

AtomicOutput::~AtomicOutput() {
  if (committed_) return;
  remove_with_side_files(temp_path_);
  forget_temp_path(temp_path_);
  remove_made_directories_above(temp_path_);
}

void AtomicOutput::commit() {
  check_not_an_input(final_path_);
  std::error_code ec;
  if (!overwrite_ && fs::exists(final_path_, ec))
    throw Error(ErrorClass::output, "write",
                quote(final_path_) + " appeared while writing; pass --overwrite to replace it");
  std::lock_guard<std::recursive_mutex> lock(unfinished().mutex);
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0)
    throw Error(ErrorClass::output, "write",
                "cannot move the finished output to " + quote(final_path_) + ": " +
                    std::strerror(errno));
  committed_ = true;
  forget_temp_path(temp_path_);
}

void remove_unfinished_outputs() {
  UnfinishedOutputs& u = unfinished();
  std::lock_guard<std::recursive_mutex> lock(u.mutex);
  for (const std::string& path : u.temp_paths) remove_with_side_files(path);
  for (const std::string& path : u.temp_paths) remove_made_directories_above(path);
  u.temp_paths.clear();
}

void remove_unfinished_outputs_on_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  int num_signals = 0;
  for (int sig : kCleanupSignals) {
    // A signal ignored from the start (nohup's SIGHUP, SIGINT of a background job) stays
    // ignored: blocked and waited for, it would be received.
    struct sigaction current {};
    if (sigaction(sig, nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;
    sigaddset(&signals, sig);
    ++num_signals;
  }
  if (num_signals == 0 || pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0) return;
  std::thread([signals] {
    int sig = 0;
    if (sigwait(&signals, &sig) != 0) return;
    // The lock stays held until the process ends: no output starts or moves meanwhile.
    UnfinishedOutputs& u = unfinished();
    u.mutex.lock();
    const std::size_t removed = u.temp_paths.size();
    remove_unfinished_outputs();
    const char* name = sigabbrev_np(sig);
    // On a terminal, first clear a progress line left without its newline.
    if (isatty(STDERR_FILENO)) std::fputs("\r\033[K", stderr);
    std::fprintf(stderr, "isoquad: stopped by SIG%s%s\n", name ? name : "?",
                 removed > 0 ? "; the unfinished outputs were removed" : "");
    std::signal(sig, SIG_DFL);
    sigset_t just;
    sigemptyset(&just);
    sigaddset(&just, sig);
    pthread_sigmask(SIG_UNBLOCK, &just, nullptr);
    raise(sig);
    _exit(128 + sig);
  }).detach();
}

void write_text_file(const std::string& path, const std::string& text, bool overwrite) {
  AtomicOutput out(path, overwrite);
  {
    std::ofstream f(out.temp_path());
    f << text;
    f.close();
    if (!f) throw Error(ErrorClass::output, "write", quote(path) + ": cannot write");
  }
  out.commit();
}

namespace {

// `final_path`'s key (output_path_key), or Error(usage) when `keys` has it.
std::string key_not_given_twice(const std::vector<std::string>& keys,
                                const std::string& final_path) {
  const std::string key = output_path_key(final_path);
  if (std::find(keys.begin(), keys.end(), key) != keys.end())
    throw Error(ErrorClass::usage, "write",
                quote(final_path) +
                    " would be written twice: given twice, or given once and also written "
                    "beside another output (a .gr3's .ll, a .slf's .cli)");
  return key;
}

}  // namespace

void OutputPathCheck::add(const std::string& final_path, bool overwrite) {
  const std::string key = key_not_given_twice(paths_, final_path);
  check_output_path(final_path, overwrite);
  paths_.push_back(key);
}

const std::string& OutputSet::add(const std::string& final_path, bool overwrite) {
  const std::string key = key_not_given_twice(paths_, final_path);
  outputs_.push_back(std::make_unique<AtomicOutput>(final_path, overwrite));
  paths_.push_back(key);
  overwrite_.push_back(overwrite);
  return outputs_.back()->temp_path();
}

void OutputSet::remove_on_commit(const std::string& path) {
  std::error_code ec;
  removed_.push_back(output_path_key(path));
}

Error OutputSet::explained(const Error& e) const {
  if (e.error_class() != ErrorClass::output) return e;
  std::string message = e.message();
  std::string full;
  for (const auto& o : outputs_) {
    // Whole paths first, then bare names (GDAL and SQLite name files their own way).
    const std::string names[2] = {o->temp_path(),
                                  std::filesystem::path(o->temp_path()).filename().string()};
    for (const std::string& name : names)
      for (std::size_t at = message.find(name); !name.empty() && at != std::string::npos;
           at = message.find(name, at + o->final_path().size()))
        message.replace(at, name.size(), o->final_path());
    if (full.empty()) {
      std::error_code ec;
      const std::filesystem::path dir =
          std::filesystem::absolute(o->final_path(), ec).parent_path();
      const std::filesystem::space_info space = std::filesystem::space(dir, ec);
      if (!ec && space.available < (1u << 20))
        full = " (the disk holding " + quote(dir.string()) + " has " +
               std::to_string(space.available / 1024) + " KB free)";
    }
  }
  if (message.find(" full") == std::string::npos) message += full;
  return Error(e.error_class(), e.stage(), message);
}

void OutputSet::commit_all() {
  // A signal's clean-up waits until every output is in place (or none is).
  for (const std::string& path : paths_) check_not_an_input(path);
  for (const std::string& path : removed_) check_not_an_input(path);
  std::lock_guard<std::recursive_mutex> lock(unfinished().mutex);
  // Set aside the files being replaced (and those removed) until every output is in
  // place: paths_[i]'s in backups[i], removed_[k]'s in backups[outputs_.size() + k].
  const std::size_t n = outputs_.size();
  std::vector<std::string> backups(n + removed_.size());
  auto path_of = [&](std::size_t i) -> const std::string& {
    return i < n ? paths_[i] : removed_[i - n];
  };
  auto restore = [&] {
    for (std::size_t i = 0; i < backups.size(); ++i)
      if (!backups[i].empty()) std::rename(backups[i].c_str(), path_of(i).c_str());
  };
  std::error_code ec;
  for (std::size_t i = 0; i < backups.size(); ++i) {
    if ((i < n && !overwrite_[i]) || !fs::is_regular_file(path_of(i), ec)) continue;
    const std::string backup = path_of(i) + ".isoquad-old-" + std::to_string(getpid());
    if (std::rename(path_of(i).c_str(), backup.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      restore();
      throw Error(
          ErrorClass::output, "write",
          "cannot " + std::string(i < n ? "replace " : "remove ") + quote(path_of(i)) + ": " + why);
    }
    backups[i] = backup;
  }
  std::size_t done = 0;
  try {
    for (; done < n; ++done) outputs_[done]->commit();
  } catch (...) {
    for (std::size_t i = 0; i < done; ++i) std::remove(paths_[i].c_str());
    restore();
    throw;
  }
  for (const std::string& b : backups)
    if (!b.empty()) std::remove(b.c_str());
}

}  // namespace isoquad
