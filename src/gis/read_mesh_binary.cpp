// The binary formats of read_mesh: UGRID netCDF (and D-Flow FM's older net files) and
// TELEMAC's Selafin, with the boundary conditions' .cli beside it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <netcdf.h>

#include "core/error.h"
#include "core/text.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "gis/read_mesh_formats.h"

namespace isoquad::mesh_readers {

namespace {

// A netCDF file open for reading; Error(input) naming the file for each failure.
class NcReader {
 public:
  explicit NcReader(const std::string& path) : path_(path) {
    const int status = nc_open(path.c_str(), NC_NOWRITE, &id_);
    if (status == NC_NOERR) return;
    // A file that begins as one (classic CDF, or netCDF-4's HDF5) but does not open: cut
    // short or damaged.
    std::string head(8, '\0');
    std::ifstream in(path, std::ios::binary);
    in.read(head.data(), 8);
    const bool looks_like_one = head.compare(0, 3, "CDF") == 0 || head == "\x89HDF\r\n\x1a\n";
    throw Error(
        ErrorClass::input, "read",
        "'" + path + "': " +
            (looks_like_one ? "an incomplete or damaged netCDF file (" : "not a netCDF file (") +
            nc_strerror(status) + (looks_like_one ? "): was it written or copied whole?" : ")"));
  }
  ~NcReader() { nc_close(id_); }
  NcReader(const NcReader&) = delete;
  NcReader& operator=(const NcReader&) = delete;

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorClass::input, "read", "'" + path_ + "': " + what);
  }
  // The variable's id; -1 when there is none.
  int find(const std::string& name) const {
    int var = -1;
    return nc_inq_varid(id_, name.c_str(), &var) == NC_NOERR ? var : -1;
  }
  int need(const std::string& name, const std::string& why) const {
    const int var = find(name);
    if (var < 0) fail("no variable '" + name + "' (" + why + ")");
    return var;
  }
  // A text attribute; empty when there is none.
  std::string text(int var, const char* name) const {
    nc_type type;
    std::size_t length = 0;
    if (nc_inq_att(id_, var, name, &type, &length) != NC_NOERR || type != NC_CHAR) return "";
    std::string value(length, '\0');
    if (nc_get_att_text(id_, var, name, value.data()) != NC_NOERR) return "";
    while (!value.empty() && value.back() == '\0') value.pop_back();
    return value;
  }
  // An integer attribute; `otherwise` when there is none.
  long long integer(int var, const char* name, long long otherwise) const {
    long long value = 0;
    nc_type type;
    std::size_t length = 0;
    if (nc_inq_att(id_, var, name, &type, &length) != NC_NOERR || length != 1 || type == NC_CHAR)
      return otherwise;
    return nc_get_att_longlong(id_, var, name, &value) == NC_NOERR ? value : otherwise;
  }
  // A numeric attribute; `otherwise` when there is none.
  double number(int var, const char* name, double otherwise) const {
    double value = 0;
    nc_type type;
    std::size_t length = 0;
    if (nc_inq_att(id_, var, name, &type, &length) != NC_NOERR || length != 1 || type == NC_CHAR)
      return otherwise;
    return nc_get_att_double(id_, var, name, &value) == NC_NOERR ? value : otherwise;
  }
  nc_type type(int var) const {
    nc_type t = NC_NAT;
    nc_inq_vartype(id_, var, &t);
    return t;
  }
  std::vector<std::size_t> shape(int var) const {
    int ndims = 0;
    nc_inq_varndims(id_, var, &ndims);
    std::vector<int> dims(ndims);
    nc_inq_vardimid(id_, var, dims.data());
    std::vector<std::size_t> out;
    for (int d : dims) {
      std::size_t n = 0;
      nc_inq_dimlen(id_, d, &n);
      out.push_back(n);
    }
    return out;
  }
  std::string dim_name(int var, int k) const {
    int ndims = 0;
    nc_inq_varndims(id_, var, &ndims);
    std::vector<int> dims(ndims);
    nc_inq_vardimid(id_, var, dims.data());
    char name[NC_MAX_NAME + 1] = {};
    if (k < ndims) nc_inq_dimname(id_, dims[k], name);
    return name;
  }
  std::vector<double> doubles(int var) const {
    std::size_t n = 1;
    for (std::size_t d : shape(var)) n *= d;
    std::vector<double> values(n);
    if (n && nc_get_var_double(id_, var, values.data()) != NC_NOERR) fail("cannot read a variable");
    return values;
  }
  std::vector<long long> integers(int var) const {
    std::size_t n = 1;
    for (std::size_t d : shape(var)) n *= d;
    std::vector<long long> values(n);
    if (n && nc_get_var_longlong(id_, var, values.data()) != NC_NOERR)
      fail("cannot read a variable");
    return values;
  }
  int num_vars() const {
    int n = 0;
    nc_inq_nvars(id_, &n);
    return n;
  }
  std::string var_name(int var) const {
    char name[NC_MAX_NAME + 1] = {};
    nc_inq_varname(id_, var, name);
    return name;
  }

 private:
  std::string path_;
  int id_ = -1;
};

// The CRS of a coordinate variable: its grid mapping's WKT (crs_wkt, spatial_ref, wkt)
// or EPSG code (epsg, epsg_code); EPSG:4326 for longitudes; empty when unknown.
std::string netcdf_crs(const NcReader& nc, int x) {
  const std::string mapping = nc.text(x, "grid_mapping");
  std::vector<std::string> candidates;
  if (!mapping.empty()) candidates.push_back(mapping);
  for (const char* name : {"projected_coordinate_system", "wgs84", "crs"})
    candidates.push_back(name);
  for (const std::string& name : candidates) {
    const int var = nc.find(name);
    if (var < 0) continue;
    for (const char* att : {"crs_wkt", "spatial_ref", "wkt"}) {
      const std::string wkt = nc.text(var, att);
      if (!wkt.empty()) return wkt;
    }
    const std::string code = nc.text(var, "epsg_code");
    if (!code.empty() && code != "EPSG:0") return code;
    const long long epsg = nc.integer(var, "epsg", 0);
    if (epsg > 0) return "EPSG:" + std::to_string(epsg);
  }
  const std::string standard = nc.text(x, "standard_name");
  if (standard == "longitude" || nc.text(x, "units") == "degrees_east") return "EPSG:4326";
  return "";
}

}  // namespace

// A netCDF file is a mesh when it holds one (UGRID's 2D mesh topology, or a D-Flow FM
// net file's nodes); otherwise a grid, as GEBCO's and ETOPO's are, for GDAL to read as
// a raster. One that netCDF cannot open is left to the mesh reader's message.
bool netcdf_holds_mesh(const std::string& path) {
  const std::lock_guard<std::recursive_mutex> netcdf(netcdf_mutex());
  int id = -1;
  if (nc_open(path.c_str(), NC_NOWRITE, &id) != NC_NOERR) return true;
  int num_vars = 0, var = -1;
  nc_inq_nvars(id, &num_vars);
  bool mesh = nc_inq_varid(id, "NetNode_x", &var) == NC_NOERR;
  for (int v = 0; v < num_vars && !mesh; ++v) {
    nc_type type;
    std::size_t length = 0;
    if (nc_inq_att(id, v, "cf_role", &type, &length) != NC_NOERR || type != NC_CHAR) continue;
    std::string role(length, '\0');
    if (nc_get_att_text(id, v, "cf_role", role.data()) == NC_NOERR)
      mesh = role.rfind("mesh_topology", 0) == 0;
  }
  nc_close(id);
  return mesh;
}

// UGRID-1.0 (the first variable with cf_role mesh_topology and topology_dimension 2:
// its node coordinates and face_node_connectivity, numbered from start_index, with
// _FillValue or negative numbers for missing corners), or D-Flow FM's older net file
// (NetNode_x, NetNode_y, NetElemNode numbered from 1).
void read_netcdf(const std::string& path, ReadMesh& mesh) {
  const std::lock_guard<std::recursive_mutex> netcdf(netcdf_mutex());
  const NcReader nc(path);
  int topology = -1;
  for (int v = 0; v < nc.num_vars() && topology < 0; ++v)
    if (nc.text(v, "cf_role") == "mesh_topology" && nc.integer(v, "topology_dimension", 0) == 2)
      topology = v;
  int x = -1, y = -1, faces = -1, z = -1;
  long long start = 0;
  bool transposed = false;
  if (topology >= 0) {
    const std::string name = nc.var_name(topology);
    // The nodes' bed levels: a variable on the mesh's nodes named *_node_z, or of
    // standard_name altitude.
    for (int v = 0; v < nc.num_vars() && z < 0; ++v) {
      const std::string var = nc.var_name(v);
      if (nc.text(v, "mesh") == name && nc.text(v, "location") == "node" &&
          (nc.text(v, "standard_name") == "altitude" ||
           (var.size() > 7 && var.compare(var.size() - 7, 7, "_node_z") == 0)))
        z = v;
    }
    std::istringstream coordinates(nc.text(topology, "node_coordinates"));
    std::string xn, yn;
    if (!(coordinates >> xn >> yn)) nc.fail("mesh topology '" + name + "' has no node_coordinates");
    x = nc.need(xn, name + "'s node_coordinates");
    y = nc.need(yn, name + "'s node_coordinates");
    const std::string face_name = nc.text(topology, "face_node_connectivity");
    faces = nc.need(face_name, name + "'s face_node_connectivity");
    start = nc.integer(faces, "start_index", 0);
    const std::string face_dim = nc.text(topology, "face_dimension");
    transposed = !face_dim.empty() && nc.dim_name(faces, 1) == face_dim;
  } else if (nc.find("NetNode_x") >= 0) {
    x = nc.need("NetNode_x", "a D-Flow FM net file's nodes");
    y = nc.need("NetNode_y", "a D-Flow FM net file's nodes");
    faces = nc.need("NetElemNode", "a D-Flow FM net file's cells");
    z = nc.find("NetNode_z");
    start = 1;
  } else {
    nc.fail(
        "no 2D mesh: no variable with cf_role mesh_topology and topology_dimension 2 "
        "(UGRID), and no NetNode_x (a D-Flow FM net file)");
  }
  const std::vector<double> xs = nc.doubles(x), ys = nc.doubles(y);
  if (xs.size() != ys.size()) nc.fail("the node coordinates differ in length");
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]))
      nc.fail("node " + std::to_string(i + start) + " has no finite coordinates");
    mesh.points.push_back({xs[i], ys[i]});
  }
  mesh.crs = netcdf_crs(nc, x);
  if (z >= 0) {
    mesh.node_values = nc.doubles(z);
    const int kind = nc.type(z);
    const double fill =
        nc.number(z, "_FillValue", kind == NC_FLOAT ? NC_FILL_FLOAT : NC_FILL_DOUBLE);
    for (double& v : mesh.node_values)
      if (v == fill || !std::isfinite(v)) v = std::numeric_limits<double>::quiet_NaN();
    if (mesh.node_values.size() != mesh.points.size()) mesh.node_values.clear();
  }
  const std::vector<std::size_t> shape = nc.shape(faces);
  if (shape.size() != 2) nc.fail("the face-node connectivity is not a 2D array");
  const std::size_t num_faces = shape[transposed ? 1 : 0], width = shape[transposed ? 0 : 1];
  const std::vector<long long> table = nc.integers(faces);
  const long long fill = nc.integer(faces, "_FillValue", NC_FILL_INT);
  const long long np = static_cast<long long>(mesh.points.size());
  for (std::size_t f = 0; f < num_faces; ++f) {
    std::vector<int> nodes;
    for (std::size_t k = 0; k < width; ++k) {
      const long long n = table[transposed ? k * num_faces + f : f * width + k];
      if (n == fill || n < start) continue;
      if (n - start >= np)
        nc.fail("face " + std::to_string(f + 1) + " has node " + std::to_string(n) +
                ", beyond the " + std::to_string(np) + " nodes (numbered from " +
                std::to_string(start) + ")");
      nodes.push_back(static_cast<int>(n - start));
    }
    if (nodes.size() != 3 && nodes.size() != 4)
      nc.fail("face " + std::to_string(f + 1) + " has " + std::to_string(nodes.size()) +
              " nodes: only triangles and quadrangles are read");
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (std::size_t j = i + 1; j < nodes.size(); ++j)
        if (nodes[i] == nodes[j])
          nc.fail("face " + std::to_string(f + 1) + " has the same node twice");
    if (nodes.size() == 3)
      mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
    else
      mesh.quads.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
  }
}

namespace {

// TELEMAC's Selafin (.slf): Fortran sequential records (a 4-byte length before and after),
// big-endian (or little-endian, told by the first record's length, 80): the title (its
// last 8 characters SERAFIN, or SERAFIND for doubles), the numbers of variables, their
// names, IPARAM (10 integers; a date follows when the tenth is 1; the third and fourth
// an origin added to the coordinates), NELEM NPOIN NDP 1, IKLE (numbered from 1), IPOBO,
// X and Y. The time steps after them are not read.
class SelafinReader {
 public:
  explicit SelafinReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) fail("cannot open the mesh file");
    unsigned char b[4];
    if (!in_.read(reinterpret_cast<char*>(b), 4)) fail("empty, not a Selafin file");
    big_ = (b[0] << 24 | b[1] << 16 | b[2] << 8 | b[3]) == 80;
    if (!big_ && (b[3] << 24 | b[2] << 16 | b[1] << 8 | b[0]) != 80)
      fail("not a Selafin file (its first record is not an 80-character title)");
    in_.seekg(0);
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ErrorClass::input, "read", "'" + path_ + "': " + what);
  }
  // The next record's bytes.
  std::string record(const char* what) {
    const std::int64_t length = raw_int(what);
    if (length < 0 || length > (std::int64_t{1} << 34))
      fail(std::string("a damaged record (") + what + ")");
    std::string bytes(static_cast<std::size_t>(length), '\0');
    if (!in_.read(bytes.data(), length)) fail(std::string("the file ends inside ") + what);
    if (raw_int(what) != length) fail(std::string("a damaged record (") + what + ")");
    return bytes;
  }
  std::vector<std::int32_t> ints(const char* what, std::size_t at_least) {
    const std::string r = record(what);
    if (r.size() % 4 || r.size() / 4 < at_least)
      fail(std::string("the record of ") + what + " holds " + std::to_string(r.size()) + " bytes");
    std::vector<std::int32_t> out(r.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::int32_t>(word(r, 4 * i));
    return out;
  }
  bool at_end() { return in_.peek() == std::char_traits<char>::eof(); }
  std::vector<double> reals(const char* what, std::size_t count, bool doubles) {
    const std::string r = record(what);
    const std::size_t width = doubles ? 8 : 4;
    if (r.size() != count * width)
      fail(std::string("the record of ") + what + " holds " + std::to_string(r.size()) +
           " bytes, not " + std::to_string(count * width));
    std::vector<double> out(count);
    for (std::size_t i = 0; i < count; ++i) {
      if (doubles) {
        const std::uint64_t bits =
            std::uint64_t{word(r, 8 * i + (big_ ? 0 : 4))} << 32 | word(r, 8 * i + (big_ ? 4 : 0));
        std::memcpy(&out[i], &bits, 8);
      } else {
        const std::uint32_t bits = word(r, 4 * i);
        float f;
        std::memcpy(&f, &bits, 4);
        out[i] = f;
      }
    }
    return out;
  }

 private:
  std::uint32_t word(const std::string& r, std::size_t at) const {
    const auto* b = reinterpret_cast<const unsigned char*>(r.data() + at);
    return big_ ? std::uint32_t{b[0]} << 24 | b[1] << 16 | b[2] << 8 | b[3]
                : std::uint32_t{b[3]} << 24 | b[2] << 16 | b[1] << 8 | b[0];
  }
  std::int64_t raw_int(const char* what) {
    char b[4];
    if (!in_.read(b, 4)) fail(std::string("the file ends before ") + what);
    return static_cast<std::int32_t>(word(std::string(b, 4), 0));
  }
  std::string path_;
  std::ifstream in_;
  bool big_ = true;
};

}  // namespace

void read_selafin(const std::string& path, ReadMesh& mesh) {
  SelafinReader r(path);
  const std::string title = r.record("the title");
  if (title.size() != 80) r.fail("not a Selafin file (its title is not 80 characters)");
  const bool doubles = title.substr(72, 8).rfind("SERAFIND", 0) == 0;
  const std::vector<std::int32_t> counts = r.ints("the numbers of variables", 2);
  // The bed level's variable: BOTTOM (FOND in French), its name the record's first 16
  // characters.
  int bottom = -1;
  for (int i = 0; i < counts[0] + counts[1]; ++i) {
    std::string name = r.record("a variable's name").substr(0, 16);
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (bottom < 0 && i < counts[0] && (lower_case(name) == "bottom" || lower_case(name) == "fond"))
      bottom = i;
  }
  const std::vector<std::int32_t> iparam = r.ints("IPARAM", 10);
  if (iparam[9] == 1) r.record("the date");
  const std::vector<std::int32_t> sizes = r.ints("NELEM NPOIN NDP", 3);
  const std::int32_t nelem = sizes[0], npoin = sizes[1], ndp = sizes[2];
  if (nelem < 0 || npoin <= 0) r.fail("a damaged record (NELEM NPOIN NDP)");
  if (ndp != 3 && ndp != 4)
    r.fail("elements of " + std::to_string(ndp) +
           " nodes: only triangles and quadrangles are read");
  const std::vector<std::int32_t> ikle = r.ints("IKLE", static_cast<std::size_t>(nelem) * ndp);
  if (ikle.size() != static_cast<std::size_t>(nelem) * ndp)
    r.fail("IKLE does not hold NELEM x NDP nodes");
  r.record("IPOBO");
  const std::vector<double> x = r.reals("X", npoin, doubles), y = r.reals("Y", npoin, doubles);
  for (std::int32_t i = 0; i < npoin; ++i)
    mesh.points.push_back({x[i] + iparam[2], y[i] + iparam[3]});
  for (std::int32_t e = 0; e < nelem; ++e) {
    std::vector<int> nodes;
    for (int k = 0; k < ndp; ++k) {
      const std::int32_t n = ikle[static_cast<std::size_t>(e) * ndp + k];
      if (n < 1 || n > npoin)
        r.fail("element " + std::to_string(e + 1) + " has node " + std::to_string(n) +
               ", not among the " + std::to_string(npoin) + " nodes");
      nodes.push_back(n - 1);
    }
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (std::size_t j = i + 1; j < nodes.size(); ++j)
        if (nodes[i] == nodes[j])
          r.fail("element " + std::to_string(e + 1) + " has the same node twice");
    if (ndp == 3)
      mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
    else
      mesh.quads.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
  }
  // The bed level at the first time step, when the file has one.
  if (bottom < 0 || r.at_end()) return;
  r.record("the first time step's time");
  for (int i = 0; i <= bottom; ++i) {
    std::vector<double> values = r.reals("a variable at the first time step", npoin, doubles);
    if (i == bottom) mesh.node_values = std::move(values);
  }
}

// TELEMAC's boundary conditions beside its geometry (geo.cli beside geo.slf), when there:
// a line per boundary node, LIHBOR first and the node (from 1) twelfth of 13 fields; a
// node of LIHBOR 2 (a wall) is land, any other (4 free, 5 prescribed, 6 incident waves)
// open, and the faces between two open nodes of one LIHBOR are open boundaries
// (open_boundaries_from_codes).
void read_telemac_cli(const std::string& slf_path, ReadMesh& mesh) {
  const std::string cli = std::filesystem::path(slf_path).replace_extension(".cli").string();
  if (!std::filesystem::is_regular_file(cli)) return;
  LineReader r(cli);
  std::vector<long long> codes(mesh.points.size(), 0);
  std::string line;
  while (r.next(line)) {
    Fields f(line, r);
    if (f.at_end()) continue;
    const long long lihbor = f.integer("LIHBOR");
    for (int k = 0; k < 10; ++k) f.word("the boundary condition's fields");
    const long long node = f.integer("the node (the 12th field)");
    if (node < 1 || node > static_cast<long long>(mesh.points.size()))
      r.fail("node " + std::to_string(node) + " is not among the geometry's " +
             std::to_string(mesh.points.size()) + " nodes");
    codes[node - 1] = lihbor == 2 ? 1 : 2 + std::max(0LL, lihbor);
  }
  open_boundaries_from_codes(codes, cli, mesh);
}

}  // namespace isoquad::mesh_readers
