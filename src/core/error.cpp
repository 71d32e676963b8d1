#include "core/error.h"

namespace isoquad {

int exit_code(ErrorClass cls) {
  switch (cls) {
    case ErrorClass::usage: return 2;
    case ErrorClass::input: return 3;
    case ErrorClass::crs: return 4;
    case ErrorClass::meshing: return 5;
    case ErrorClass::output: return 6;
    case ErrorClass::internal: return 70;
  }
  return 70;
}

const char* error_class_name(ErrorClass cls) {
  switch (cls) {
    case ErrorClass::usage: return "usage";
    case ErrorClass::input: return "input";
    case ErrorClass::crs: return "crs";
    case ErrorClass::meshing: return "meshing";
    case ErrorClass::output: return "output";
    case ErrorClass::internal: return "internal";
  }
  return "internal";
}

Error::Error(ErrorClass cls, std::string stage, const std::string& message)
    : std::runtime_error(stage + ": " + message),
      cls_(cls),
      stage_(std::move(stage)),
      message_(message) {}

}  // namespace isoquad
