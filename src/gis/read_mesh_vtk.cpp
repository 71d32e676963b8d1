// The VTK formats of read_mesh: the XML unstructured grid (.vtu: ascii, binary or appended
// data, raw or base64, uncompressed or zlib-compressed, as VTK, ParaView, meshio and
// isoquad write it) and the legacy ASCII file (.vtk, versions 2 to 5.1). Triangles and
// quadrangles (and polygons of 3 or 4 points) are read; vertices and lines skipped; the
// other cells refused. Neither format holds a CRS.
#include <cpl_conv.h>
#include <cpl_minixml.h>
#include <cpl_string.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "gis/gdal_env.h"
#include "gis/read_mesh_formats.h"

namespace isoquad::mesh_readers {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(ErrorClass::input, "read", "'" + path + "': " + what);
}

// The cells into the mesh: VTK's types 5 (triangle), 9 (quad), 7 (polygon of 3 or 4
// points) kept; 1, 2, 3 and 4 (vertices, lines) counted as skipped; the others refused.
void add_cells(const std::string& path, const std::vector<std::int64_t>& connectivity,
               const std::vector<std::int64_t>& offsets, const std::vector<std::int64_t>& types,
               ReadMesh& mesh) {
  const std::size_t np = mesh.points.size();
  if (offsets.size() != types.size())
    fail(path, std::to_string(offsets.size()) + " cell offsets for " +
                   std::to_string(types.size()) + " cell types");
  std::int64_t start = 0;
  for (std::size_t c = 0; c < types.size(); ++c) {
    const std::int64_t end = offsets[c];
    if (end < start || end > static_cast<std::int64_t>(connectivity.size()))
      fail(path, "cell " + std::to_string(c) + "'s offset " + std::to_string(end) +
                     " is out of order or past the connectivity's " +
                     std::to_string(connectivity.size()) + " entries");
    const std::size_t n = static_cast<std::size_t>(end - start);
    const std::int64_t type = types[c];
    if (type >= 1 && type <= 4) {
      ++mesh.num_skipped_elements;
    } else if ((type == 5 && n == 3) || (type == 9 && n == 4) ||
               (type == 7 && (n == 3 || n == 4))) {
      std::array<int, 4> v{};
      for (std::size_t k = 0; k < n; ++k) {
        const std::int64_t id = connectivity[static_cast<std::size_t>(start) + k];
        if (id < 0 || id >= static_cast<std::int64_t>(np))
          fail(path, "cell " + std::to_string(c) + " has point " + std::to_string(id) +
                         ", which is not among the file's " + std::to_string(np) + " points");
        v[k] = static_cast<int>(id);
      }
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
          if (v[i] == v[j]) fail(path, "cell " + std::to_string(c) + " has the same point twice");
      if (n == 3)
        mesh.triangles.push_back({v[0], v[1], v[2]});
      else
        mesh.quads.push_back(v);
    } else {
      fail(path, "cell " + std::to_string(c) + " is of VTK type " + std::to_string(type) +
                     " with " + std::to_string(n) +
                     " points: only triangles (5) and quadrangles (9) are read, as 2D elements");
    }
    start = end;
  }
}

// --- .vtu -----------------------------------------------------------------------------

struct VtuFile {
  std::string path;
  bool header64 = false;    // header_type UInt64 (else UInt32)
  bool compressed = false;  // vtkZLibDataCompressor
  std::string appended;     // the AppendedData's bytes after its '_'
  bool appended_raw = false;
};

std::size_t type_size(const std::string& path, const std::string& type) {
  if (type == "Int8" || type == "UInt8") return 1;
  if (type == "Int16" || type == "UInt16") return 2;
  if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
  if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
  fail(path, "a DataArray of type '" + type + "', which VTK does not define");
}

double value_at(const unsigned char* p, const std::string& type) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  if (type == "Int8") return get(std::int8_t{});
  if (type == "UInt8") return get(std::uint8_t{});
  if (type == "Int16") return get(std::int16_t{});
  if (type == "UInt16") return get(std::uint16_t{});
  if (type == "Int32") return get(std::int32_t{});
  if (type == "UInt32") return get(std::uint32_t{});
  if (type == "Int64") return get(std::int64_t{});
  if (type == "UInt64") return get(std::uint64_t{});
  if (type == "Float32") return get(float{});
  return get(double{});
}

std::string base64_decoded(std::string text) {
  text.push_back('\0');
  const int n = CPLBase64DecodeInPlace(reinterpret_cast<GByte*>(text.data()));
  text.resize(static_cast<std::size_t>(std::max(0, n)));
  return text;
}

std::uint64_t header_word(const std::string& bytes, std::size_t k, bool header64) {
  if (header64) {
    std::uint64_t v = 0;
    std::memcpy(&v, bytes.data() + 8 * k, 8);
    return v;
  }
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + 4 * k, 4);
  return v;
}

// The data of a binary or appended array: `encoded` from its start (base64 when `base64`,
// else raw bytes), its header (the byte count, or the compressed blocks' sizes) first.
std::string array_bytes(const VtuFile& f, const std::string& encoded, bool base64,
                        const std::string& name) {
  const std::size_t h = f.header64 ? 8 : 4;
  // The first n bytes of the stream (base64: the first characters that hold them).
  auto first_bytes = [&](std::size_t n) {
    if (!base64) {
      if (n > encoded.size()) fail(f.path, "the data of '" + name + "' end early");
      return encoded.substr(0, n);
    }
    const std::size_t chars = (n + 2) / 3 * 4;
    if (chars > encoded.size()) fail(f.path, "the data of '" + name + "' end early");
    return base64_decoded(encoded.substr(0, chars)).substr(0, n);
  };
  if (!f.compressed) {
    const std::string head = first_bytes(h);
    const std::uint64_t n = header_word(head, 0, f.header64);
    if (n > (std::uint64_t{1} << 40)) fail(f.path, "the data of '" + name + "' are too long");
    return first_bytes(h + n).substr(h);
  }
  // Compressed: [blocks, block size, last block's size, each block's compressed size],
  // base64-encoded apart from the blocks.
  const std::uint64_t blocks = header_word(first_bytes(3 * h), 0, f.header64);
  if (blocks > (1u << 24)) fail(f.path, "the data of '" + name + "' have too many blocks");
  const std::size_t header_bytes = (3 + blocks) * h;
  const std::string head = first_bytes(header_bytes);
  const std::uint64_t block_size = header_word(head, 1, f.header64);
  const std::uint64_t last_size = header_word(head, 2, f.header64);
  std::uint64_t total = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) total += header_word(head, 3 + b, f.header64);
  std::string packed;
  if (base64) {
    const std::size_t head_chars = (header_bytes + 2) / 3 * 4;
    const std::size_t data_chars = (total + 2) / 3 * 4;
    if (head_chars + data_chars > encoded.size())
      fail(f.path, "the data of '" + name + "' end early");
    packed = base64_decoded(encoded.substr(head_chars, data_chars));
  } else {
    if (header_bytes + total > encoded.size()) fail(f.path, "the data of '" + name + "' end early");
    packed = encoded.substr(header_bytes, total);
  }
  std::string out;
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t size = header_word(head, 3 + b, f.header64);
    const std::uint64_t raw = b + 1 == blocks && last_size > 0 ? last_size : block_size;
    std::string block(raw, '\0');
    std::size_t got = 0;
    if (at + size > packed.size() ||
        !CPLZLibInflate(packed.data() + at, size, block.data(), block.size(), &got) || got != raw)
      fail(f.path, "the compressed data of '" + name + "' cannot be inflated");
    out += block;
    at += size;
  }
  return out;
}

// A DataArray's values, `count` of them (the array's tuples times its components).
std::vector<double> array_values(const VtuFile& f, const CPLXMLNode* array, std::size_t count) {
  const std::string name = CPLGetXMLValue(array, "Name", "");
  const std::string type = CPLGetXMLValue(array, "type", "");
  const std::string format = CPLGetXMLValue(array, "format", "ascii");
  std::vector<double> values;
  if (format == "ascii") {
    std::istringstream in(CPLGetXMLValue(array, "", ""));
    double v = 0;
    while (values.size() < count && in >> v) values.push_back(v);
  } else {
    std::string bytes;
    if (format == "binary") {
      std::string text = CPLGetXMLValue(array, "", "");
      text.erase(std::remove_if(text.begin(), text.end(),
                                [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
                 text.end());
      bytes = array_bytes(f, text, true, name);
    } else if (format == "appended") {
      const std::size_t offset = static_cast<std::size_t>(
          std::strtoull(CPLGetXMLValue(array, "offset", "0"), nullptr, 10));
      if (offset > f.appended.size()) fail(f.path, "'" + name + "' starts past the appended data");
      bytes = array_bytes(f, f.appended.substr(offset), !f.appended_raw, name);
    } else {
      fail(f.path, "'" + name + "' is in format '" + format + "' (ascii, binary or appended)");
    }
    const std::size_t size = type_size(f.path, type);
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    for (std::size_t i = 0; i + size <= bytes.size() && values.size() < count; i += size)
      values.push_back(value_at(p + i, type));
  }
  if (values.size() < count)
    fail(f.path, "'" + name + "' holds " + std::to_string(values.size()) + " values, not " +
                     std::to_string(count));
  return values;
}

const CPLXMLNode* named_array(const CPLXMLNode* parent, const std::string& name) {
  for (const CPLXMLNode* c = parent ? parent->psChild : nullptr; c; c = c->psNext)
    if (c->eType == CXT_Element && std::strcmp(c->pszValue, "DataArray") == 0 &&
        name == CPLGetXMLValue(c, "Name", ""))
      return c;
  return nullptr;
}

void read_vtu(const std::string& path, ReadMesh& mesh) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the mesh file");
  std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  VtuFile f;
  f.path = path;
  // Appended data (raw bytes, not XML) taken out before the XML is parsed.
  const std::size_t appended_at = doc.find("<AppendedData");
  if (appended_at != std::string::npos) {
    const std::size_t tag_end = doc.find('>', appended_at);
    const std::size_t mark = doc.find('_', tag_end);
    const std::size_t close = doc.rfind("</AppendedData>");
    if (tag_end == std::string::npos || mark == std::string::npos || close == std::string::npos ||
        close < mark)
      fail(path, "its AppendedData is not closed");
    f.appended_raw =
        doc.substr(appended_at, tag_end - appended_at).find("\"raw\"") != std::string::npos;
    f.appended = doc.substr(mark + 1, close - mark - 1);
    if (!f.appended_raw)
      f.appended.erase(
          std::remove_if(f.appended.begin(), f.appended.end(),
                         [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
          f.appended.end());
    doc.erase(tag_end + 1, close - tag_end - 1);
  }
  std::string parse_error;
  const std::unique_ptr<CPLXMLNode, decltype(&CPLDestroyXMLNode)> root(
      [&] {
        const GdalErrorCapture capture;  // the parser's complaint, for the message
        CPLXMLNode* node = CPLParseXMLString(doc.c_str());
        parse_error = capture.last_message();
        return node;
      }(),
      &CPLDestroyXMLNode);
  // A file cut short (a copy or a write that stopped) still begins as one.
  if (!root && doc.find("<VTKFile") != std::string::npos)
    fail(path, "an incomplete or damaged VTK XML file (" +
                   (parse_error.empty() ? std::string("its XML does not parse") : parse_error) +
                   "): was it written or copied whole?");
  const CPLXMLNode* file = root ? CPLGetXMLNode(root.get(), "=VTKFile") : nullptr;
  if (!file) fail(path, "not a VTK XML file (no VTKFile element)");
  if (std::string(CPLGetXMLValue(file, "type", "")) != "UnstructuredGrid")
    fail(path, std::string("a VTK XML file of type '") + CPLGetXMLValue(file, "type", "") +
                   "': only an UnstructuredGrid (.vtu) is read");
  if (std::string(CPLGetXMLValue(file, "byte_order", "LittleEndian")) != "LittleEndian")
    fail(path, "its data are big-endian: only little-endian files are read");
  f.header64 = std::string(CPLGetXMLValue(file, "header_type", "UInt32")) == "UInt64";
  const std::string compressor = CPLGetXMLValue(file, "compressor", "");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    fail(path,
         "data compressed by " + compressor + ": only zlib's (vtkZLibDataCompressor) are read");
  f.compressed = !compressor.empty();
  const CPLXMLNode* piece = CPLGetXMLNode(file, "UnstructuredGrid.Piece");
  if (!piece) fail(path, "no UnstructuredGrid Piece");
  if (piece->psNext && piece->psNext->eType == CXT_Element &&
      std::strcmp(piece->psNext->pszValue, "Piece") == 0)
    fail(path, "several pieces: only a grid of one piece is read");
  const std::size_t np = static_cast<std::size_t>(
      std::strtoull(CPLGetXMLValue(piece, "NumberOfPoints", "0"), nullptr, 10));
  const std::size_t nc = static_cast<std::size_t>(
      std::strtoull(CPLGetXMLValue(piece, "NumberOfCells", "0"), nullptr, 10));
  const CPLXMLNode* points = CPLGetXMLNode(piece, "Points.DataArray");
  if (!points) fail(path, "no Points");
  const std::size_t components =
      static_cast<std::size_t>(std::atoi(CPLGetXMLValue(points, "NumberOfComponents", "1")));
  if (components < 2 || components > 3)
    fail(path, "points of " + std::to_string(components) + " components");
  const std::vector<double> xyz = array_values(f, points, np * components);
  for (std::size_t i = 0; i < np; ++i) {
    const Point2 p{xyz[i * components], xyz[i * components + 1]};
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      fail(path, "point " + std::to_string(i) + " is not finite");
    mesh.points.push_back(p);
  }
  const CPLXMLNode* cells = CPLGetXMLNode(piece, "Cells");
  const CPLXMLNode* conn = named_array(cells, "connectivity");
  const CPLXMLNode* offs = named_array(cells, "offsets");
  const CPLXMLNode* types = named_array(cells, "types");
  if (!conn || !offs || !types) fail(path, "its Cells lack connectivity, offsets or types");
  auto integers = [](const std::vector<double>& v) {
    return std::vector<std::int64_t>(v.begin(), v.end());
  };
  const std::vector<std::int64_t> offsets = integers(array_values(f, offs, nc));
  const std::size_t nconn =
      offsets.empty() ? 0 : static_cast<std::size_t>(std::max<std::int64_t>(0, offsets.back()));
  add_cells(path, integers(array_values(f, conn, nconn)), offsets,
            integers(array_values(f, types, nc)), mesh);
}

// --- legacy .vtk ------------------------------------------------------------------------

void read_legacy_vtk(const std::string& path, ReadMesh& mesh) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open the mesh file");
  std::string line;
  std::getline(in, line);
  if (line.rfind("# vtk DataFile", 0) != 0) fail(path, "not a VTK file (no '# vtk DataFile' line)");
  std::getline(in, line);  // the title
  std::string word;
  in >> word;
  if (word != "ASCII") fail(path, "a binary legacy VTK file: only ASCII ones are read");
  std::string dataset;
  in >> word >> dataset;
  if (word != "DATASET" || dataset != "UNSTRUCTURED_GRID")
    fail(path, "a legacy VTK " + dataset + ": only an UNSTRUCTURED_GRID is read");
  std::vector<std::int64_t> connectivity, offsets, types;
  auto need = [&](const std::string& what) {
    if (!in) fail(path, "cannot read " + what);
  };
  while (in >> word) {
    if (word == "POINTS") {
      std::size_t n = 0;
      in >> n >> word;
      need("POINTS");
      for (std::size_t i = 0; i < n; ++i) {
        double x = 0, y = 0, z = 0;
        in >> x >> y >> z;
        need("point " + std::to_string(i));
        mesh.points.push_back({x, y});
      }
    } else if (word == "CELLS") {
      std::size_t n = 0, size = 0;
      in >> n >> size;
      need("CELLS");
      // Version 5: OFFSETS and CONNECTIVITY arrays; before: "k i1 .. ik" per cell.
      std::streampos at = in.tellg();
      std::string next;
      in >> next;
      if (next == "OFFSETS") {
        in >> word;  // the type
        std::vector<std::int64_t> starts(n);
        for (auto& s : starts) in >> s;
        in >> next >> word;
        if (next != "CONNECTIVITY") fail(path, "OFFSETS without CONNECTIVITY");
        connectivity.resize(size);
        for (auto& c : connectivity) in >> c;
        need("the cells");
        for (std::size_t c = 1; c < n; ++c) offsets.push_back(starts[c]);
      } else {
        in.seekg(at);
        for (std::size_t c = 0; c < n; ++c) {
          std::size_t k = 0;
          in >> k;
          need("cell " + std::to_string(c));
          for (std::size_t i = 0; i < k; ++i) {
            std::int64_t v = 0;
            in >> v;
            connectivity.push_back(v);
          }
          need("cell " + std::to_string(c));
          offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        }
      }
    } else if (word == "CELL_TYPES") {
      std::size_t n = 0;
      in >> n;
      types.resize(n);
      for (auto& t : types) in >> t;
      need("CELL_TYPES");
    } else if (word == "CELL_DATA" || word == "POINT_DATA") {
      break;  // the data arrays are not read
    }
  }
  add_cells(path, connectivity, offsets, types, mesh);
}

}  // namespace

void read_vtk(const std::string& path, ReadMesh& mesh) {
  if (mesh.format == "vtu")
    read_vtu(path, mesh);
  else
    read_legacy_vtk(path, mesh);
}

}  // namespace isoquad::mesh_readers
