#include "gis/gdal_env.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogrsf_frmts.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <regex>
#include <vector>

#include "core/error.h"
#include "core/text.h"
#include "gis/atomic_output.h"
#include "gis/model_lines.h"

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

// GDAL's message on one line: some span several (PostgreSQL's connection failures,
// indented with tabs), which our one-line errors quote.
void CPL_STDCALL capture_handler(CPLErr level, CPLErrorNum, const char* msg) {
  if (level < CE_Warning || !msg) return;
  g_last_message.clear();
  bool space = false;
  for (const char* c = msg; *c; ++c) {
    if (*c == '\n' || *c == '\r' || *c == '\t' || *c == ' ') {
      space = !g_last_message.empty();
      continue;
    }
    if (space) g_last_message += ' ';
    space = false;
    g_last_message += *c;
  }
}
}  // namespace

GdalErrorCapture::GdalErrorCapture() {
  g_last_message.clear();
  CPLPushErrorHandler(capture_handler);
}

GdalErrorCapture::~GdalErrorCapture() { CPLPopErrorHandler(); }

std::string GdalErrorCapture::last_message() const { return g_last_message; }

namespace {

struct PooledDataset {
  std::string key;  // the path and the open options
  GDALDataset* ds = nullptr;
  bool in_use = false;
};

std::mutex g_pool_mutex;
int g_pool_users = 0;  // live VectorDatasetPool objects
std::vector<PooledDataset> g_pool;

std::string pool_key(const std::string& path, const std::vector<std::string>& open_options) {
  std::string key = path;
  for (const std::string& o : open_options) key += '\n' + o;
  return key;
}

// A kept data set of `key` that nobody uses, marked used; nullptr if none (or no pool).
GDALDataset* take_pooled(const std::string& key) {
  const std::lock_guard<std::mutex> lock(g_pool_mutex);
  if (g_pool_users == 0) return nullptr;
  for (PooledDataset& p : g_pool) {
    if (p.in_use || p.key != key) continue;
    p.in_use = true;
    return p.ds;
  }
  return nullptr;
}

// Keeps a data set just opened for `key`, in use; false without a pool.
bool add_pooled(const std::string& key, GDALDataset* ds) {
  const std::lock_guard<std::mutex> lock(g_pool_mutex);
  if (g_pool_users == 0) return false;
  g_pool.push_back({key, ds, true});
  return true;
}

// Puts a kept data set back, as a fresh open would give it; false when the pool has
// ended since (the caller closes it).
bool return_pooled(GDALDataset* ds) {
  auto find = [ds] {
    return std::find_if(g_pool.begin(), g_pool.end(),
                        [ds](const PooledDataset& p) { return p.ds == ds; });
  };
  {
    const std::lock_guard<std::mutex> lock(g_pool_mutex);
    const auto it = find();
    if (it == g_pool.end()) return false;
    if (g_pool_users == 0) {
      g_pool.erase(it);
      return false;
    }
  }
  // Still marked in use: nobody else takes it meanwhile.
  for (int i = 0; i < ds->GetLayerCount(); ++i) {
    OGRLayer* layer = ds->GetLayer(i);
    layer->SetAttributeFilter(nullptr);
    layer->SetSpatialFilter(nullptr);
    layer->ResetReading();
  }
  const std::lock_guard<std::mutex> lock(g_pool_mutex);
  const auto it = find();
  if (g_pool_users == 0) {  // the pool ended while the layers were reset
    g_pool.erase(it);
    return false;
  }
  it->in_use = false;
  return true;
}

}  // namespace

void GdalDatasetCloser::operator()(GDALDataset* ds) const {
  if (pooled && return_pooled(ds)) return;
  GDALClose(ds);
}

VectorDatasetPool::VectorDatasetPool() {
  const std::lock_guard<std::mutex> lock(g_pool_mutex);
  ++g_pool_users;
}

VectorDatasetPool::~VectorDatasetPool() {
  std::vector<GDALDataset*> unused;
  {
    const std::lock_guard<std::mutex> lock(g_pool_mutex);
    if (--g_pool_users > 0) return;
    // Data sets still in use are closed when their users let them go (return_pooled).
    for (auto it = g_pool.begin(); it != g_pool.end();) {
      if (it->in_use) {
        ++it;
      } else {
        unused.push_back(it->ds);
        it = g_pool.erase(it);
      }
    }
  }
  for (GDALDataset* ds : unused) GDALClose(ds);
}

namespace {

// GDAL's virtual file system for an archive's name, or "" for another file (or a path
// GDAL's virtual file systems already name).
std::string archive_prefix(const std::string& path) {
  if (path.rfind("/vsi", 0) == 0) return "";
  const std::string name = lower_case(path);
  if (ends_with(name, ".zip")) return "/vsizip/";
  if (ends_with(name, ".tar") || ends_with(name, ".tgz") || ends_with(name, ".tar.gz"))
    return "/vsitar/";
  if (ends_with(name, ".gz")) return "/vsigzip/";
  return "";
}

// Whether a member of an archive is a file (or a File Geodatabase's directory) of the
// kind asked for, by its extension.
bool is_data_member(const std::string& member, ArchiveContent content) {
  static const char* const kVector[] = {".shp", ".gpkg", ".geojson", ".json", ".topojson", ".kml",
                                        ".gml", ".fgb",  ".sqlite",  ".tab",  ".mif",      ".gdb"};
  static const char* const kRaster[] = {".tif", ".tiff", ".nc",  ".asc", ".vrt", ".img",
                                        ".grd", ".bil",  ".hgt", ".jp2", ".dem", ".bag"};
  const std::string name = lower_case(member);
  if (content == ArchiveContent::vector) {
    for (const char* ext : kVector)
      if (ends_with(name, ext)) return true;
  } else {
    for (const char* ext : kRaster)
      if (ends_with(name, ext)) return true;
  }
  return false;
}

bool gdal_opens(const std::string& path, ArchiveContent content) {
  std::unique_lock<std::recursive_mutex> lock;
  if (content == ArchiveContent::raster) lock = gdal_raster_lock();
  GdalErrorCapture capture;  // quiet: a failure here only means "look inside"
  const unsigned flags =
      (content == ArchiveContent::vector ? GDAL_OF_VECTOR : GDAL_OF_RASTER) | GDAL_OF_READONLY;
  GdalDataset ds(
      static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), flags, nullptr, nullptr, nullptr)));
  return ds && (content == ArchiveContent::raster || ds->GetLayerCount() > 0);
}

std::string joined(const std::vector<std::string>& names, std::size_t at_most) {
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < at_most; ++i) text += (i ? ", " : "") + names[i];
  if (names.size() > at_most) text += " and " + std::to_string(names.size() - at_most) + " more";
  return text;
}

}  // namespace

std::recursive_mutex& netcdf_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

std::unique_lock<std::recursive_mutex> gdal_raster_lock() {
  return std::unique_lock<std::recursive_mutex>(netcdf_mutex());
}

std::string gdal_path(const std::string& path, ArchiveContent content, std::string& problem) {
  ensure_gdal_registered();
  note_input_file(path);  // no output may replace it
  problem.clear();
  const std::string prefix = archive_prefix(path);
  if (prefix.empty()) return path;
  const std::string root = prefix + path;
  // A gzipped file is one file: GDAL's own error, if any, comes when it is opened.
  if (prefix == "/vsigzip/" || gdal_opens(root, content)) return root;
  std::vector<std::string> all, data;
  char** list = VSIReadDirRecursive(root.c_str());
  for (char** entry = list; entry && *entry; ++entry) {
    std::string member = *entry;
    if (!member.empty() && member.back() == '/') member.pop_back();
    if (member.empty()) continue;
    all.push_back(member);
    if (is_data_member(member, content)) data.push_back(member);
  }
  CSLDestroy(list);
  std::sort(all.begin(), all.end());
  std::sort(data.begin(), data.end());
  const char* kind = content == ArchiveContent::vector ? "vector" : "raster";
  if (data.size() == 1) return root + "/" + data[0];
  if (data.empty()) {
    problem = std::string("the archive holds no ") + kind + " file GDAL reads" +
              (all.empty() ? std::string(" (it is empty or unreadable)")
                           : " (it holds " + joined(all, 8) + ")");
  } else {
    problem = std::string("the archive holds ") + std::to_string(data.size()) + " " + kind +
              " files (" + joined(data, 8) + "): name one, e.g. " + root + "/" + data[0];
  }
  return "";
}

bool is_data_source_name(const std::string& path) {
  const std::size_t colon = path.find(':');
  if (colon == std::string::npos || colon < 2) return false;  // nor a drive letter
  for (std::size_t i = 0; i < colon; ++i)
    if (!std::isalnum(static_cast<unsigned char>(path[i])) && path[i] != '_') return false;
  struct stat st {};
  return stat(path.c_str(), &st) != 0;
}

GdalDataset open_vector_dataset(const std::string& path, const std::string& stage,
                                const std::vector<std::string>& open_options) {
  ensure_gdal_registered();
  auto fail = [&](const std::string& what) {
    throw Error(ErrorClass::input, stage, "'" + path + "': " + what);
  };
  struct stat st {};
  const bool named_source = is_data_source_name(path);
  // /vsi paths (zip, curl...) and data sources named for a driver are GDAL's business;
  // plain paths we check ourselves.
  if (path.rfind("/vsi", 0) != 0 && !named_source) {
    if (stat(path.c_str(), &st) != 0) fail("no such file or directory");
    if (S_ISREG(st.st_mode) && st.st_size == 0) fail("file is empty");
  }
  if (is_model_lines_file(path)) return read_model_lines(path, stage);
  const std::string key = pool_key(path, open_options);
  if (GDALDataset* kept = take_pooled(key)) return GdalDataset(kept, GdalDatasetCloser{true});
  std::string problem;
  const std::string open_path =
      named_source ? path : gdal_path(path, ArchiveContent::vector, problem);
  if (open_path.empty()) fail(problem);
  GdalErrorCapture capture;
  std::vector<const char*> options;
  for (const std::string& o : open_options) options.push_back(o.c_str());
  options.push_back(nullptr);
  GdalDataset ds(static_cast<GDALDataset*>(GDALOpenEx(
      open_path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, options.data(), nullptr)));
  if (!ds) {
    const std::string why = capture.last_message();
    if (named_source)
      fail("no such file, nor a data source GDAL opens" + (why.empty() ? "" : ": " + why));
    fail("cannot read as a vector data set" +
         (why.empty() ? std::string(" (unknown or corrupt format)") : " (" + why + ")"));
  }
  if (ds->GetLayerCount() == 0) fail("contains no vector layer");
  if (add_pooled(key, ds.get())) return GdalDataset(ds.release(), GdalDatasetCloser{true});
  return ds;
}

namespace {

// Up to `limit` bytes of a file GDAL can open (a member of an archive too); empty when
// it cannot be read.
std::string file_head(const std::string& path, std::size_t limit) {
  if (path.rfind("/vsistdin", 0) == 0) return "";  // read once, by GDAL
  VSILFILE* f = VSIFOpenL(path.c_str(), "rb");
  if (!f) return "";
  std::string text(limit, '\0');
  text.resize(VSIFReadL(text.data(), 1, limit, f));
  VSIFCloseL(f);
  return text;
}

// Why PROJ does not take `text` as a CRS (its message, or "not a CRS"); empty if it does.
std::string crs_rejection(const std::string& text) {
  OGRSpatialReference srs;
  GdalErrorCapture capture;
  if (srs.SetFromUserInput(text.c_str()) == OGRERR_NONE) return "";
  const std::string why = capture.last_message();
  return why.empty() ? "not a CRS" : why;
}

}  // namespace

std::string declared_crs_problem(GDALDataset& ds, OGRLayer& layer) {
  const std::string driver = ds.GetDriver() ? ds.GetDriver()->GetDescription() : "";
  const std::string path = ds.GetDescription();
  {
    GdalErrorCapture quiet;  // a shapefile's .prj is read when first asked for: its
    layer.GetSpatialRef();   // errors are said below in our words
  }
  if (driver == "GeoJSON") {
    // The "crs" member comes before the features in the files that have one (GDAL and
    // QGIS write it there); the start of the file is enough.
    std::string head = file_head(path, 1 << 20);
    head.resize(std::min(head.size(), head.find("\"features\"")));
    const std::size_t at = head.find("\"crs\"");
    if (at == std::string::npos) return "";
    const std::string member = head.substr(at, 1000);  // the member, not the whole head
    static const std::regex named(R"re(^"crs"\s*:\s*\{[^{}]*\{[^{}]*"name"\s*:\s*"([^"]*)")re");
    std::smatch m;
    if (!std::regex_search(member, m, named)) return "";
    const std::string why = crs_rejection(m[1].str());
    if (why.empty()) return "";
    return "its \"crs\" member names '" + m[1].str() + "', a CRS GDAL and PROJ do not know (" +
           why + "), which GDAL reads as WGS 84";
  }
  if (driver == "ESRI Shapefile" && !layer.GetSpatialRef()) {
    // A directory of shapefiles is one data set; the layer is one file of it.
    VSIStatBufL st;
    const bool directory = VSIStatL(path.c_str(), &st) == 0 && VSI_ISDIR(st.st_mode);
    const std::string base =
        directory ? std::string(CPLFormFilename(path.c_str(), layer.GetName(), "shp")) : path;
    for (const char* ext : {"prj", "PRJ"}) {
      const std::string prj = CPLResetExtension(base.c_str(), ext);
      if (VSIStatL(prj.c_str(), &st) != 0 || !VSI_ISREG(st.st_mode)) continue;
      const std::string why = crs_rejection(file_head(prj, 1 << 16));
      if (why.empty()) return "";
      return "its .prj file '" + std::string(CPLGetFilename(prj.c_str())) +
             "' holds no CRS GDAL can read (" + why + ")";
    }
  }
  return "";
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
