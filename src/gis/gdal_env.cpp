#include "gis/gdal_env.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogrsf_frmts.h>
#include <sys/stat.h>

#include <mutex>

#include "core/error.h"

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

void GdalDatasetCloser::operator()(GDALDataset* ds) const {
  GDALClose(ds);
}

GdalDataset open_vector_dataset(const std::string& path, const std::string& stage) {
  ensure_gdal_registered();
  auto fail = [&](const std::string& what) {
    throw Error(ErrorClass::input, stage, "'" + path + "': " + what);
  };
  struct stat st {};
  // /vsi paths (zip, curl...) are GDAL's business; plain paths we check ourselves.
  if (path.rfind("/vsi", 0) != 0) {
    if (stat(path.c_str(), &st) != 0) fail("no such file or directory");
    if (S_ISREG(st.st_mode) && st.st_size == 0) fail("file is empty");
  }
  GdalErrorCapture capture;
  GdalDataset ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds) {
    const std::string why = capture.last_message();
    fail("cannot read as a vector data set" +
         (why.empty() ? std::string(" (unknown or corrupt format)") : " (" + why + ")"));
  }
  if (ds->GetLayerCount() == 0) fail("contains no vector layer");
  return ds;
}

std::string layer_names(GDALDataset& ds) {
  std::string names;
  for (int i = 0; i < ds.GetLayerCount(); ++i)
    names += (i ? ", " : "") + std::string(ds.GetLayer(i)->GetName());
  return names;
}

std::string field_names(OGRLayer& layer) {
  OGRFeatureDefn* defn = layer.GetLayerDefn();
  std::string names;
  for (int i = 0; i < defn->GetFieldCount(); ++i)
    names += (i ? ", " : "") + std::string(defn->GetFieldDefn(i)->GetNameRef());
  return names.empty() ? "none" : names;
}

}  // namespace isoquad
