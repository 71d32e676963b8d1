// A domain from a raster of elevations or depths (a DEM): the area where its values lie
// in [zmin, zmax] (--zmin, --zmax), as a sea below the 0 m contour or a floodplain below
// +10 m. The contour at the range's ends (GDAL's contour generator, linear between cell
// centres) bounds it; cells without a value are outside it. The area read is the
// raster's extent, or its part under --bbox or --clip; where the domain reaches that
// area's edge, its boundary is open (the sea goes on beyond the data), elsewhere land.
#pragma once

#include <cstddef>
#include <string>

#include "gis/read_polygons.h"

namespace isoquad {

// Whether `path` is a raster INPUT: GDAL opens it as a raster and not as a vector file
// (a GeoPackage of tiles, a GeoTIFF, a netCDF grid). False for a path GDAL cannot open,
// whose error the vector reader gives.
bool is_raster_input(const std::string& path);

// The polygons outside the domain (cells out of [zmin, zmax] or without a value, with
// the domain's lakes in them as holes) in the raster's CRS (or --src-crs), and as
// bbox_ring the area read, so that the water domain of select_domain (the area minus
// the polygons) is the domain. read.zmin or read.zmax must be set. A window of more
// than read.max_raster_cells cells is read averaged onto a coarser grid (raster_note
// says so). Throws Error(input) for a raster GDAL cannot read, an area that misses it
// or no cell in the range, Error(crs) for a raster without a CRS and no --src-crs.
SourceData read_raster_domain(const ReadParams& read);

}  // namespace isoquad
