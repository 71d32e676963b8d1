// GDAL/OGR set-up shared by every reader and writer.
#pragma once

#include <string>

namespace isoquad {

// Registers GDAL's drivers once; safe to call from every entry point.
void ensure_gdal_registered();

// While alive, GDAL's own messages are kept instead of printed; last_message() gives
// the most recent error (or warning) text, so it can be put into our own error.
class GdalErrorCapture {
 public:
  GdalErrorCapture();
  ~GdalErrorCapture();
  GdalErrorCapture(const GdalErrorCapture&) = delete;
  GdalErrorCapture& operator=(const GdalErrorCapture&) = delete;
  std::string last_message() const;
};

}  // namespace isoquad
