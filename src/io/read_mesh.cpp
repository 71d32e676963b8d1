#include "io/read_mesh.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <unordered_map>

#include "core/error.h"

namespace isoquad {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The file's lines, one at a time, with their numbers for the messages.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw Error(ErrorClass::input, "read", "'" + path + "': cannot open the mesh file");
  }
  // The next line (without a trailing carriage return); false at the end of the file.
  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }
  // The next line that holds something; Error(input) at the end of the file.
  std::string need(const std::string& what) {
    std::string line;
    while (next(line))
      if (line.find_first_not_of(" \t") != std::string::npos) return line;
    throw Error(ErrorClass::input, "read",
                "'" + path_ + "': the file ends at line " + std::to_string(number_) + " where " +
                    what + " should follow");
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(number_, what); }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw Error(ErrorClass::input, "read",
                "'" + path_ + "' line " + std::to_string(line) + ": " + what);
  }
  int number() const { return number_; }

 private:
  std::string path_;
  std::ifstream in_;
  int number_ = 0;
};

// Whitespace-separated fields of a line, read as numbers.
class Fields {
 public:
  Fields(const std::string& line, const LineReader& reader) : line_(line), reader_(reader) {}
  bool at_end() {
    skip();
    return pos_ >= line_.size();
  }
  std::string word(const char* what) {
    skip();
    if (pos_ >= line_.size()) reader_.fail(std::string("expected ") + what);
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !std::isspace(static_cast<unsigned char>(line_[pos_]))) ++pos_;
    return line_.substr(start, pos_ - start);
  }
  long long integer(const char* what) {
    const std::string w = word(what);
    long long value = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (ec != std::errc() || end != w.data() + w.size())
      reader_.fail(std::string("expected ") + what + ", an integer, found '" + w + "'");
    return value;
  }
  double number(const char* what) {
    const std::string w = word(what);
    double value = 0;
    // Fortran writes exponents as D.
    std::string text = w;
    std::replace(text.begin(), text.end(), 'D', 'E');
    std::replace(text.begin(), text.end(), 'd', 'e');
    const char* first = text.data();
    if (!text.empty() && text[0] == '+') ++first;
    const auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
      reader_.fail(std::string("expected ") + what + ", a number, found '" + w + "'");
    return value;
  }
  std::string rest() {
    skip();
    return line_.substr(std::min(pos_, line_.size()));
  }

 private:
  void skip() {
    while (pos_ < line_.size() && std::isspace(static_cast<unsigned char>(line_[pos_]))) ++pos_;
  }
  std::string line_;
  const LineReader& reader_;
  std::size_t pos_ = 0;
};

// Node ids as the file numbers them, to indices into ReadMesh::points.
class NodeIds {
 public:
  void add(long long id, const LineReader& reader) {
    if (!index_.emplace(id, static_cast<int>(index_.size())).second)
      reader.fail("node " + std::to_string(id) + " is given twice");
  }
  // The node's index; -1 when the file has no such node.
  int find(long long id) const {
    const auto it = index_.find(id);
    return it == index_.end() ? -1 : it->second;
  }
  int at(long long id, const LineReader& reader, long long element) const {
    const int index = find(id);
    if (index < 0)
      reader.fail("element " + std::to_string(element) + " has node " + std::to_string(id) +
                  ", which is not among the file's nodes");
    return index;
  }

 private:
  std::unordered_map<long long, int> index_;
};

// An element's nodes (3 or 4 of them) into the mesh.
void add_element(ReadMesh& mesh, const std::vector<int>& nodes, const LineReader& reader,
                 long long id) {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t j = i + 1; j < nodes.size(); ++j)
      if (nodes[i] == nodes[j])
        reader.fail("element " + std::to_string(id) + " has the same node twice");
  if (nodes.size() == 3)
    mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
  else
    mesh.quads.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
}

long long need_count(Fields& f, const char* what, const LineReader& reader) {
  const long long n = f.integer(what);
  if (n < 0) reader.fail(std::string(what) + " is negative");
  return n;
}

// SCHISM's hgrid.gr3 / hgrid.ll and ADCIRC's fort.14: a title, "NE NP", NP lines
// "id x y depth", NE lines "id k n1 .. nk"; the boundaries after them are not read.
void read_gr3(LineReader& r, ReadMesh& mesh) {
  r.need("a title line");
  const std::string counts = r.need("the numbers of elements and nodes");
  Fields f(counts, r);
  const long long ne = need_count(f, "the number of elements", r);
  const long long np = need_count(f, "the number of nodes", r);
  NodeIds ids;
  mesh.points.reserve(np);
  for (long long k = 0; k < np; ++k) {
    const std::string line = r.need("node " + std::to_string(k + 1) + " of " + std::to_string(np));
    Fields n(line, r);
    ids.add(n.integer("a node id"), r);
    const double x = n.number("x");
    mesh.points.push_back({x, n.number("y")});
  }
  std::vector<int> nodes;
  for (long long k = 0; k < ne; ++k) {
    const std::string line =
        r.need("element " + std::to_string(k + 1) + " of " + std::to_string(ne));
    Fields e(line, r);
    const long long id = e.integer("an element id");
    const long long kind = e.integer("the element's number of nodes");
    if (kind != 3 && kind != 4)
      r.fail("element " + std::to_string(id) + " has " + std::to_string(kind) +
             " nodes: only triangles (3) and quadrangles (4) are read");
    nodes.clear();
    for (long long i = 0; i < kind; ++i) nodes.push_back(ids.at(e.integer("a node id"), r, id));
    add_element(mesh, nodes, r, id);
  }
}

// SMS's .2dm: cards ND (nodes), E3T and E4Q (elements); the others (MESH2D, NS,
// MESHNAME...) skipped, second-order elements refused.
void read_2dm(LineReader& r, ReadMesh& mesh) {
  NodeIds ids;
  struct Pending {
    long long id;
    std::vector<long long> nodes;
    int line;
  };
  std::vector<Pending> elements;  // nodes may follow the elements
  std::string line;
  while (r.next(line)) {
    Fields f(line, r);
    if (f.at_end()) continue;
    const std::string card = f.word("a card");
    if (card == "ND") {
      ids.add(f.integer("a node id"), r);
      const double x = f.number("x");
      mesh.points.push_back({x, f.number("y")});
    } else if (card == "E3T" || card == "E4Q") {
      Pending p{f.integer("an element id"), {}, r.number()};
      for (int i = 0; i < (card == "E3T" ? 3 : 4); ++i) p.nodes.push_back(f.integer("a node id"));
      elements.push_back(std::move(p));
    } else if (card == "E6T" || card == "E8Q" || card == "E9Q" || card == "E2L" || card == "E3L") {
      r.fail("element card " + card + ": only E3T and E4Q (triangles and quadrangles) are read");
    }
  }
  if (mesh.points.empty()) r.fail("no ND (node) card in the file");
  std::vector<int> nodes;
  for (const Pending& p : elements) {
    nodes.clear();
    for (long long id : p.nodes) {
      const int index = ids.find(id);
      if (index < 0)  // the message names the element's own line
        r.fail_at(p.line, "element " + std::to_string(p.id) + " has node " + std::to_string(id) +
                              ", which is not among the ND cards");
      nodes.push_back(index);
    }
    add_element(mesh, nodes, r, p.id);
  }
}

// Gmsh's element types read: 2 (3-node triangle), 3 (4-node quadrangle); 1 (line) and
// 15 (point) skipped; the others refused.
int msh_element_nodes(long long type, const LineReader& r) {
  if (type == 2) return 3;
  if (type == 3) return 4;
  if (type == 1 || type == 15) return type == 1 ? -2 : -1;
  r.fail("Gmsh element type " + std::to_string(type) +
         ": only triangles (2) and quadrangles (3) are read, with lines (1) and points (15) "
         "skipped (second-order or 3D elements are not)");
}

// Gmsh's .msh, ASCII, version 2.2 or 4.1 ($Nodes and $Elements; the other sections
// skipped).
void read_msh(LineReader& r, ReadMesh& mesh) {
  std::string line;
  double version = 0;
  NodeIds ids;
  bool has_nodes = false, has_elements = false;
  std::vector<int> nodes;
  while (r.next(line)) {
    if (line == "$MeshFormat") {
      Fields f(r.need("the format's version"), r);
      version = f.number("the format's version");
      const long long file_type = f.integer("the file type");
      if (file_type != 0)
        r.fail(
            "a binary .msh: save the mesh as ASCII (Gmsh: -format msh41 without -bin, "
            "or Mesh.Binary = 0)");
      if (version < 2 || version >= 5 || (version >= 3 && version < 4))
        r.fail("version " + std::to_string(version) + " of the .msh format: 2.2 and 4.1 are read");
    } else if (line == "$Nodes") {
      if (version == 0) r.fail("$Nodes before $MeshFormat");
      has_nodes = true;
      if (version < 3) {
        Fields c(r.need("the number of nodes"), r);
        const long long n = need_count(c, "the number of nodes", r);
        for (long long k = 0; k < n; ++k) {
          Fields f(r.need("a node"), r);
          ids.add(f.integer("a node tag"), r);
          const double x = f.number("x");
          mesh.points.push_back({x, f.number("y")});
        }
      } else {
        Fields c(r.need("the nodes' counts"), r);
        const long long blocks = need_count(c, "the number of entity blocks", r);
        for (long long b = 0; b < blocks; ++b) {
          Fields h(r.need("an entity block of nodes"), r);
          h.integer("the entity's dimension");
          h.integer("the entity's tag");
          h.integer("whether the nodes are parametric");
          const long long n = need_count(h, "the block's number of nodes", r);
          std::vector<long long> tags(n);
          for (long long k = 0; k < n; ++k) {
            Fields t(r.need("a node tag"), r);
            tags[k] = t.integer("a node tag");
          }
          for (long long k = 0; k < n; ++k) {
            Fields f(r.need("a node's coordinates"), r);
            ids.add(tags[k], r);
            const double x = f.number("x");
            mesh.points.push_back({x, f.number("y")});  // z and parametric ones ignored
          }
        }
      }
      if (r.need("$EndNodes") != "$EndNodes") r.fail("expected $EndNodes");
    } else if (line == "$Elements") {
      if (!has_nodes) r.fail("$Elements before $Nodes");
      has_elements = true;
      if (version < 3) {
        Fields c(r.need("the number of elements"), r);
        const long long n = need_count(c, "the number of elements", r);
        for (long long k = 0; k < n; ++k) {
          Fields f(r.need("an element"), r);
          const long long id = f.integer("an element tag");
          const int count = msh_element_nodes(f.integer("the element type"), r);
          const long long tags = need_count(f, "the number of tags", r);
          for (long long t = 0; t < tags; ++t) f.integer("a tag");
          if (count < 0) {
            ++mesh.num_skipped_elements;
            continue;
          }
          nodes.clear();
          for (int i = 0; i < count; ++i) nodes.push_back(ids.at(f.integer("a node tag"), r, id));
          add_element(mesh, nodes, r, id);
        }
      } else {
        Fields c(r.need("the elements' counts"), r);
        const long long blocks = need_count(c, "the number of entity blocks", r);
        for (long long b = 0; b < blocks; ++b) {
          Fields h(r.need("an entity block of elements"), r);
          h.integer("the entity's dimension");
          h.integer("the entity's tag");
          const int count = msh_element_nodes(h.integer("the element type"), r);
          const long long n = need_count(h, "the block's number of elements", r);
          for (long long k = 0; k < n; ++k) {
            Fields f(r.need("an element"), r);
            const long long id = f.integer("an element tag");
            if (count < 0) {
              ++mesh.num_skipped_elements;
              continue;
            }
            nodes.clear();
            for (int i = 0; i < count; ++i) nodes.push_back(ids.at(f.integer("a node tag"), r, id));
            add_element(mesh, nodes, r, id);
          }
        }
      }
      if (r.need("$EndElements") != "$EndElements") r.fail("expected $EndElements");
    }
  }
  if (version == 0) r.fail("no $MeshFormat section: not a Gmsh .msh file");
  if (!has_nodes || !has_elements) r.fail("no $Nodes or no $Elements section");
}

// MIKE 21/3 FM's .mesh: "itemtype unit N projection", N lines "id x y z code", then
// "NE maxnodes type" and NE lines "id n1 .. n_maxnodes" (0 for a triangle's fourth).
void read_mike(LineReader& r, ReadMesh& mesh) {
  Fields h(r.need("the header"), r);
  h.integer("the item type");
  h.integer("the unit");
  const long long np = need_count(h, "the number of nodes", r);
  const std::string projection = h.rest();
  if (projection == "LONG/LAT")
    mesh.crs = "EPSG:4326";
  else if (!projection.empty() && projection != "NON-UTM")
    mesh.crs = projection;
  NodeIds ids;
  for (long long k = 0; k < np; ++k) {
    Fields f(r.need("node " + std::to_string(k + 1) + " of " + std::to_string(np)), r);
    ids.add(f.integer("a node id"), r);
    const double x = f.number("x");
    mesh.points.push_back({x, f.number("y")});
  }
  Fields c(r.need("the number of elements"), r);
  const long long ne = need_count(c, "the number of elements", r);
  const long long width = c.integer("the most nodes of an element");
  if (width != 3 && width != 4) r.fail("elements of " + std::to_string(width) + " nodes");
  std::vector<int> nodes;
  for (long long k = 0; k < ne; ++k) {
    Fields f(r.need("element " + std::to_string(k + 1) + " of " + std::to_string(ne)), r);
    const long long id = f.integer("an element id");
    nodes.clear();
    for (long long i = 0; i < width; ++i) {
      const long long node = f.integer("a node id");
      if (node == 0 && i == 3) continue;
      nodes.push_back(ids.at(node, r, id));
    }
    add_element(mesh, nodes, r, id);
  }
}

}  // namespace

std::string mesh_file_format(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string ext = lower(p.extension().string());
  const std::string name = lower(p.filename().string());
  if (ext == ".gr3" || ext == ".ll") return "gr3";
  if (ext == ".14" || ext == ".grd" || name == "fort.14") return "14";
  if (ext == ".2dm") return "2dm";
  if (ext == ".msh") return "msh";
  if (ext == ".mesh") return "mesh";
  throw Error(ErrorClass::usage, "options",
              "'" + path +
                  "': a mesh to measure is a .gr3 or .ll (SCHISM), .14 or .grd (ADCIRC), .2dm "
                  "(SMS), .msh (Gmsh, ASCII) or .mesh (MIKE 21/3 FM)");
}

ReadMesh read_mesh(const std::string& path) {
  ReadMesh mesh;
  mesh.format = mesh_file_format(path);
  if (!std::filesystem::is_regular_file(path))
    throw Error(ErrorClass::input, "read", "'" + path + "': no such mesh file");
  LineReader r(path);
  if (mesh.format == "gr3" || mesh.format == "14")
    read_gr3(r, mesh);
  else if (mesh.format == "2dm")
    read_2dm(r, mesh);
  else if (mesh.format == "msh")
    read_msh(r, mesh);
  else
    read_mike(r, mesh);
  if (mesh.quads.empty() && mesh.triangles.empty())
    throw Error(ErrorClass::input, "read",
                "'" + path + "': the mesh has no triangle or quadrangle");
  return mesh;
}

}  // namespace isoquad
