// A file written with stdio whose errors are checked: opening and closing throw
// Error(output) naming the file (its final name, `what`, for messages).
#pragma once

#include <cstdio>
#include <string>

namespace isoquad {

class OutputFile {
 public:
  OutputFile(const std::string& path, const std::string& what, const char* mode = "w");
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::FILE* get() const { return f_; }
  // Flushes and closes; throws when any write failed.
  void close();

 private:
  std::FILE* f_ = nullptr;
  std::string what_;
};

}  // namespace isoquad
