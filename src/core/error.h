// Errors that reach the user, each with a failure class mapped to one exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace isoquad {

// What kind of failure: decides the process exit code (see exit_code()).
enum class ErrorClass {
  usage,     // bad command line: unknown option, bad value, conflicting options
  input,     // the input data: missing, unreadable, invalid geometry, empty selection
  crs,       // coordinate reference systems: none given, unknown, coordinates out of range
  meshing,   // a meshing stage could not produce a valid result
  output,    // the output: exists, cannot be written
  internal,  // a bug: an invariant failed
};

// Exit codes, documented in `isoquad --help` and README.md. They avoid 124-127 and
// 137, which timeout(1) and the shell use.
int exit_code(ErrorClass cls);
const char* error_class_name(ErrorClass cls);

// An error for the user. `stage` is the pipeline stage ("read", "crs", "domain",
// "simplify", "write"...); what() gives "stage: message".
class Error : public std::runtime_error {
 public:
  Error(ErrorClass cls, std::string stage, const std::string& message);
  ErrorClass error_class() const { return cls_; }
  const std::string& stage() const { return stage_; }
  const std::string& message() const { return message_; }

 private:
  ErrorClass cls_;
  std::string stage_;
  std::string message_;
};

}  // namespace isoquad
