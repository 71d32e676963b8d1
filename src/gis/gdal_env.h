// GDAL/OGR set-up shared by every reader and writer.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

class GDALDataset;
class OGRLayer;

namespace isoquad {

// Registers GDAL's drivers once; safe to call from every entry point.
void ensure_gdal_registered();

// The netCDF library (and the HDF5 under it) is not thread-safe: every use of it, from
// opening a file to closing it, holds this lock, so that regions meshed at once (--jobs)
// may read and write .nc files. GDAL's netCDF driver has a lock of its own, which ours
// does not replace: a raster read through GDAL takes this one too (gdal_raster_lock).
std::recursive_mutex& netcdf_mutex();
// Held while a raster is opened, read and closed through GDAL, whatever its format (a
// GEBCO grid is a netCDF file, and so may be a raster without the extension).
std::unique_lock<std::recursive_mutex> gdal_raster_lock();

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

// Closes a data set; one that open_vector_dataset took from a VectorDatasetPool goes
// back to it instead.
struct GdalDatasetCloser {
  bool pooled = false;
  void operator()(GDALDataset* ds) const;
};
using GdalDataset = std::unique_ptr<GDALDataset, GdalDatasetCloser>;

// While one is alive, the vector data sets open_vector_dataset opens are kept when
// closed, and the next open of the same path with the same options gets one back, its
// layers' filters cleared and their reading reset, instead of GDAL reading the file
// again: the regions of --each read the same file, and GDAL parses a whole GeoJSON or
// TopoJSON file when it opens one (Natural Earth's countries at 1:10m: 0.4 s and 140 MB
// each time). A data set serves one user at a time: a second user at once (another
// thread) opens its own, which is kept too. Nested pools share the data sets; the last
// one to end closes them.
class VectorDatasetPool {
 public:
  VectorDatasetPool();
  ~VectorDatasetPool();
  VectorDatasetPool(const VectorDatasetPool&) = delete;
  VectorDatasetPool& operator=(const VectorDatasetPool&) = delete;
};

// Opens a vector data set read-only, with at least one layer. Throws Error(input) that
// names the file and `stage`: no such file, an empty file, not a vector format GDAL
// reads (with GDAL's reason), no layer. An archive (.zip, .tar, .tgz, .tar.gz; .gz of
// one file) is read through GDAL's virtual file systems, as downloads come (Natural
// Earth's ne_10m_land.zip): its top level as one data set, or else the one vector file
// it holds; several are named in the error, to pick one as /vsizip/FILE.zip/MEMBER.
// `open_options`: the driver's (NAME=VALUE), as ogr2ogr's -oo.
GdalDataset open_vector_dataset(const std::string& path, const std::string& stage,
                                const std::vector<std::string>& open_options = {});

// Whether `path`, which names no file, is a data source GDAL opens by name: a database or
// service connection ("PG:dbname=coast", "WFS:https://host/wfs", "MSSQL:..."), a
// driver's prefix ("GeoJSON:coast.json", "CSV:..."), a URL ("https://host/coast.geojson").
// A Windows drive ("C:") is not one.
bool is_data_source_name(const std::string& path);

enum class ArchiveContent { vector, raster };
// The path for GDAL to open `path` with: itself, unless it names an archive (see
// open_vector_dataset): then "/vsizip/path" (or /vsitar/, /vsigzip/) where GDAL opens
// that as `content` (a directory of shapefiles, an archive of one file), or else the one
// member of that kind inside. Empty, with `problem` set, when the archive holds several
// such files (named, to pick one) or none.
std::string gdal_path(const std::string& path, ArchiveContent content, std::string& problem);

// Where a file declares a CRS that GDAL could not use, so that the layer has none or
// GDAL's default (a GeoJSON file's "crs" member naming an unknown CRS leaves it WGS 84,
// a shapefile's unreadable .prj none): what is wrong, naming the CRS or file; else
// empty.
std::string declared_crs_problem(GDALDataset& ds, OGRLayer& layer);

// "name1, name2, ...": the data set's layers, for a message about a missing one.
std::string layer_names(GDALDataset& ds);
// The same for a layer's attributes ("none" without any).
std::string field_names(OGRLayer& layer);

}  // namespace isoquad
