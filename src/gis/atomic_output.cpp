#include "gis/atomic_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

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

}  // namespace

void check_output_path(const std::string& path, bool overwrite) {
  if (path.empty()) throw Error(ErrorClass::usage, "write", "empty output path");
  std::error_code ec;
  if (fs::exists(path, ec) && !overwrite)
    throw Error(ErrorClass::output, "write",
                quote(path) + " already exists; pass --overwrite to replace it");
  if (fs::is_directory(path, ec))
    throw Error(ErrorClass::output, "write", quote(path) + " is a directory");
  const fs::path dir = parent_dir(path);
  if (!fs::is_directory(dir, ec))
    throw Error(ErrorClass::output, "write",
                quote(path) + ": directory " + quote(dir.string()) + " does not exist");
  if (access(dir.c_str(), W_OK) != 0)
    throw Error(ErrorClass::output, "write",
                quote(path) + ": directory " + quote(dir.string()) + " is not writable");
}

AtomicOutput::AtomicOutput(std::string final_path, bool overwrite)
    : final_path_(std::move(final_path)), overwrite_(overwrite) {
  check_output_path(final_path_, overwrite_);
  const fs::path p(final_path_);
  const fs::path name = "." + p.stem().string() + ".tmp-" + std::to_string(getpid()) +
                        p.extension().string();
  temp_path_ = (parent_dir(final_path_) / name).string();
  remove_with_side_files(temp_path_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) remove_with_side_files(temp_path_);
}

void AtomicOutput::commit() {
  std::error_code ec;
  if (!overwrite_ && fs::exists(final_path_, ec))
    throw Error(ErrorClass::output, "write",
                quote(final_path_) + " appeared while writing; pass --overwrite to replace it");
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0)
    throw Error(ErrorClass::output, "write",
                "cannot move the finished output to " + quote(final_path_) + ": " +
                    std::strerror(errno));
  committed_ = true;
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

const std::string& OutputSet::add(const std::string& final_path, bool overwrite) {
  std::error_code ec;
  const std::string key = fs::weakly_canonical(fs::absolute(final_path, ec), ec).string();
  for (const std::string& p : paths_)
    if (p == key) throw Error(ErrorClass::usage, "write", quote(final_path) + " is given twice");
  outputs_.push_back(std::make_unique<AtomicOutput>(final_path, overwrite));
  paths_.push_back(key);
  overwrite_.push_back(overwrite);
  return outputs_.back()->temp_path();
}

void OutputSet::commit_all() {
  // Set aside the files being replaced until every output is in place.
  std::vector<std::string> backups(outputs_.size());
  auto restore = [&] {
    for (std::size_t i = 0; i < backups.size(); ++i)
      if (!backups[i].empty()) std::rename(backups[i].c_str(), paths_[i].c_str());
  };
  std::error_code ec;
  for (std::size_t i = 0; i < outputs_.size(); ++i) {
    if (!overwrite_[i] || !fs::is_regular_file(paths_[i], ec)) continue;
    const std::string backup = paths_[i] + ".isoquad-old-" + std::to_string(getpid());
    if (std::rename(paths_[i].c_str(), backup.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      restore();
      throw Error(ErrorClass::output, "write", "cannot replace " + quote(paths_[i]) + ": " + why);
    }
    backups[i] = backup;
  }
  std::size_t done = 0;
  try {
    for (; done < outputs_.size(); ++done) outputs_[done]->commit();
  } catch (...) {
    for (std::size_t i = 0; i < done; ++i) std::remove(paths_[i].c_str());
    restore();
    throw;
  }
  for (const std::string& b : backups)
    if (!b.empty()) std::remove(b.c_str());
}

}  // namespace isoquad
