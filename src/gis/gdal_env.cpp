#include "gis/gdal_env.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_api.h>

#include <mutex>

namespace isoquad {

void ensure_gdal_registered() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // Keep unclosed rings as they are in the file, so that we can report them.
    CPLSetConfigOption("OGR_GEOMETRY_ACCEPT_UNCLOSED_RING", "YES");
  });
}

namespace {
thread_local std::string g_last_message;

void CPL_STDCALL capture_handler(CPLErr level, CPLErrorNum, const char* msg) {
  if (level >= CE_Warning && msg) g_last_message = msg;
}
}  // namespace

GdalErrorCapture::GdalErrorCapture() {
  g_last_message.clear();
  CPLPushErrorHandler(capture_handler);
}

GdalErrorCapture::~GdalErrorCapture() { CPLPopErrorHandler(); }

std::string GdalErrorCapture::last_message() const { return g_last_message; }

}  // namespace isoquad
