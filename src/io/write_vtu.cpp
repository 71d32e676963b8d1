#include "io/write_vtu.h"

#include <cstdint>
#include <fstream>
#include <string>

#include "core/error.h"
#include "gis/atomic_output.h"

namespace isoquad {

namespace {

const char* kBase64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// Base64 onto a stream as the bytes come, three at a time, so that no array is copied
// and the document is never held whole (a million quads: about 170 MB of text).
class Base64Stream {
 public:
  explicit Base64Stream(std::ostream& out) : out_(out) {}
  void put(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      pending_[num_pending_++] = bytes[i];
      if (num_pending_ == 3) {
        const uint32_t v = (pending_[0] << 16) | (pending_[1] << 8) | pending_[2];
        const char quad[4] = {kBase64[(v >> 18) & 63], kBase64[(v >> 12) & 63],
                              kBase64[(v >> 6) & 63], kBase64[v & 63]};
        buffer_.append(quad, 4);
        num_pending_ = 0;
        if (buffer_.size() >= kFlush) flush();
      }
    }
  }
  // The last one or two bytes, padded with '='.
  void finish() {
    if (num_pending_ > 0) {
      const uint32_t v = (pending_[0] << 16) | (num_pending_ == 2 ? pending_[1] << 8 : 0);
      buffer_ += kBase64[(v >> 18) & 63];
      buffer_ += kBase64[(v >> 12) & 63];
      buffer_ += num_pending_ == 2 ? kBase64[(v >> 6) & 63] : '=';
      buffer_ += '=';
      num_pending_ = 0;
    }
    flush();
  }

 private:
  static constexpr std::size_t kFlush = 1 << 16;
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }
  std::ostream& out_;
  std::string buffer_;
  unsigned char pending_[3] = {0, 0, 0};
  int num_pending_ = 0;
};

// VTK's inline binary: a UInt64 byte count, then the raw little-endian values, together
// base64 encoded. `fill` hands the values to `put` in order.
template <typename Fill>
void data_array(std::ostream& out, const char* type, const std::string& name, int components,
                uint64_t nbytes, Fill&& fill) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\"";
  if (components > 1) out << " NumberOfComponents=\"" << std::to_string(components) << "\"";
  out << " format=\"binary\">\n          ";
  Base64Stream b64(out);
  b64.put(&nbytes, sizeof nbytes);
  fill(b64);
  b64.finish();
  out << "\n        </DataArray>\n";
}

void values_array(std::ostream& out, const VtuArray& a) {
  data_array(out, "Float64", a.name, 1, a.values.size() * sizeof(double), [&](Base64Stream& b) {
    if (!a.values.empty()) b.put(a.values.data(), a.values.size() * sizeof(double));
  });
}

}  // namespace

void write_vtu_document(const VtuMesh& mesh, std::ostream& out) {
  const std::vector<Point2>& pts = *mesh.points;
  for (const auto& c : mesh.cells)
    if (c.size() != 3 && c.size() != 4)
      throw Error(ErrorClass::internal, "write", "VTU cells must be triangles or quads");
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  out << "    <Piece NumberOfPoints=\"" << std::to_string(pts.size()) << "\" NumberOfCells=\""
      << std::to_string(mesh.cells.size()) << "\">\n";
  out << "      <PointData>\n";
  for (const VtuArray& a : mesh.point_data) values_array(out, a);
  out << "      </PointData>\n      <CellData>\n";
  for (const VtuArray& a : mesh.cell_data) values_array(out, a);
  out << "      </CellData>\n      <Points>\n";
  data_array(out, "Float64", "Points", 3, pts.size() * 3 * sizeof(double), [&](Base64Stream& b) {
    for (const Point2& p : pts) {
      const double xyz[3] = {p.x, p.y, 0.0};
      b.put(xyz, sizeof xyz);
    }
  });
  out << "      </Points>\n      <Cells>\n";
  std::size_t num_corners = 0;
  for (const auto& c : mesh.cells) num_corners += c.size();
  data_array(out, "Int64", "connectivity", 1, num_corners * sizeof(int64_t), [&](Base64Stream& b) {
    for (const auto& c : mesh.cells)
      for (int v : c) {
        const int64_t id = v;
        b.put(&id, sizeof id);
      }
  });
  data_array(out, "Int64", "offsets", 1, mesh.cells.size() * sizeof(int64_t), [&](Base64Stream& b) {
    int64_t offset = 0;
    for (const auto& c : mesh.cells) {
      offset += static_cast<int64_t>(c.size());
      b.put(&offset, sizeof offset);
    }
  });
  data_array(out, "UInt8", "types", 1, mesh.cells.size(), [&](Base64Stream& b) {
    for (const auto& c : mesh.cells) {
      const uint8_t type = c.size() == 3 ? 5 : 9;  // VTK_TRIANGLE, VTK_QUAD
      b.put(&type, 1);
    }
  });
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

void write_vtu(const VtuMesh& mesh, const std::string& path, bool overwrite) {
  AtomicOutput out(path, overwrite);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    write_vtu_document(mesh, f);
    f.close();
    if (!f) throw Error(ErrorClass::output, "write", "'" + path + "': cannot write");
  }
  out.commit();
}

}  // namespace isoquad
