// The line files of ocean modelling packages, which GDAL does not read: Delft3D and
// D-Flow FM's Tekal blocks (.ldb land boundaries, .pol polygons, .pli polylines) and
// Blue Kenue's .i2s line sets (TELEMAC). They carry no CRS (--src-crs gives it).
#pragma once

#include <string>

#include "gis/gdal_env.h"

namespace isoquad {

// Whether `path` names such a file, by its extension.
bool is_model_lines_file(const std::string& path);

// The file as an in-memory data set of one layer of lines named after the file, with
// the attribute `name` (a Tekal block's name; an .i2s line's value). A .pol block is
// closed where it is not. In an .ldb, the point 999.999 999.999 separates lines within a
// block. Throws Error(input), naming the file, the line number and what was expected.
GdalDataset read_model_lines(const std::string& path, const std::string& stage);

}  // namespace isoquad
