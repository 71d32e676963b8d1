#include "io/write_vtu.h"

#include <cstdint>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "gis/atomic_output.h"

namespace isoquad {

namespace {

const char* kBase64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string base64(const std::vector<unsigned char>& in) {
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
    out += kBase64[(v >> 18) & 63];
    out += kBase64[(v >> 12) & 63];
    out += kBase64[(v >> 6) & 63];
    out += kBase64[v & 63];
  }
  if (i + 1 == in.size()) {
    const uint32_t v = in[i] << 16;
    out += kBase64[(v >> 18) & 63];
    out += kBase64[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    const uint32_t v = (in[i] << 16) | (in[i + 1] << 8);
    out += kBase64[(v >> 18) & 63];
    out += kBase64[(v >> 12) & 63];
    out += kBase64[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// VTK's inline binary: a UInt64 byte count, then the raw little-endian values, together
// base64 encoded.
template <typename T>
std::string encode(const std::vector<T>& values) {
  const uint64_t nbytes = values.size() * sizeof(T);
  std::vector<unsigned char> raw(sizeof(uint64_t) + nbytes);
  std::memcpy(raw.data(), &nbytes, sizeof nbytes);
  if (nbytes) std::memcpy(raw.data() + sizeof nbytes, values.data(), nbytes);
  return base64(raw);
}

template <typename T>
void data_array(std::string& out, const char* type, const std::string& name, int components,
                const std::vector<T>& values) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"" + name + "\"";
  if (components > 1) out += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  out += " format=\"binary\">\n          " + encode(values) + "\n        </DataArray>\n";
}

}  // namespace

std::string vtu_document(const VtuMesh& mesh) {
  const std::vector<Point2>& pts = *mesh.points;
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(pts.size()) + "\" NumberOfCells=\"" +
         std::to_string(mesh.cells.size()) + "\">\n";
  out += "      <PointData>\n";
  for (const VtuArray& a : mesh.point_data) data_array(out, "Float64", a.name, 1, a.values);
  out += "      </PointData>\n      <CellData>\n";
  for (const VtuArray& a : mesh.cell_data) data_array(out, "Float64", a.name, 1, a.values);
  out += "      </CellData>\n      <Points>\n";
  std::vector<double> xyz;
  xyz.reserve(pts.size() * 3);
  for (const Point2& p : pts) xyz.insert(xyz.end(), {p.x, p.y, 0.0});
  data_array(out, "Float64", "Points", 3, xyz);
  out += "      </Points>\n      <Cells>\n";
  std::vector<int64_t> connectivity, offsets;
  std::vector<uint8_t> types;
  for (const auto& c : mesh.cells) {
    if (c.size() != 3 && c.size() != 4)
      throw Error(ErrorClass::internal, "write", "VTU cells must be triangles or quads");
    connectivity.insert(connectivity.end(), c.begin(), c.end());
    offsets.push_back(static_cast<int64_t>(connectivity.size()));
    types.push_back(c.size() == 3 ? 5 : 9);  // VTK_TRIANGLE, VTK_QUAD
  }
  data_array(out, "Int64", "connectivity", 1, connectivity);
  data_array(out, "Int64", "offsets", 1, offsets);
  data_array(out, "UInt8", "types", 1, types);
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

void write_vtu(const VtuMesh& mesh, const std::string& path, bool overwrite) {
  AtomicOutput out(path, overwrite);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << vtu_document(mesh);
    f.close();
    if (!f) throw Error(ErrorClass::output, "write", "'" + path + "': cannot write");
  }
  out.commit();
}

}  // namespace isoquad
