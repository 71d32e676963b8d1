#include "io/output_file.h"

#include "core/error.h"

namespace isoquad {

OutputFile::OutputFile(const std::string& path, const std::string& what, const char* mode)
    : f_(std::fopen(path.c_str(), mode)), what_(what) {
  if (!f_) throw Error(ErrorClass::output, "write", "'" + what + "': cannot create");
}

OutputFile::~OutputFile() {
  if (f_) std::fclose(f_);
}

void OutputFile::close() {
  const bool bad = std::ferror(f_) != 0;
  const bool closed = std::fclose(f_) == 0;
  f_ = nullptr;
  if (bad || !closed) throw Error(ErrorClass::output, "write", "'" + what_ + "': cannot write");
}

}  // namespace isoquad
