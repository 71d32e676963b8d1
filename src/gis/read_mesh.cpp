#include "gis/read_mesh.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include <netcdf.h>
#include <ogrsf_frmts.h>

#include "core/error.h"
#include "gis/crs.h"
#include "gis/gdal_env.h"
#include "gis/mesh_outline.h"

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
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  int number_ = 0;
};

// A word of the file as a message shows it: at most 32 characters, each byte outside
// printable ASCII as '?'.
std::string shown(const std::string& word) {
  std::string out;
  for (char c : word.substr(0, 32)) out += c >= 32 && c < 127 ? c : '?';
  return word.size() > 32 ? out + "..." : out;
}

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
      reader_.fail(std::string("expected ") + what + ", an integer, found '" + shown(w) + "'");
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
      reader_.fail(std::string("expected ") + what + ", a number, found '" + shown(w) + "'");
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

// A node: its id (read before) and the line's next two numbers, x and y, and with
// `value` the third one when the line has it (a depth, or z), else NaN (the rest of the
// line ignored).
void add_node(Fields& f, long long id, NodeIds& ids, ReadMesh& mesh, const LineReader& reader,
              bool value = false) {
  ids.add(id, reader);
  const double x = f.number("x");
  mesh.points.push_back({x, f.number("y")});
  if (value)
    mesh.node_values.push_back(f.at_end() ? std::numeric_limits<double>::quiet_NaN()
                                          : f.number("the node's depth or z"));
}

// A .msh element of `count` nodes (msh_element_nodes), its node tags the line's next
// numbers: a triangle or a quadrangle into the mesh; a line (count -2) into the physical
// groups of curves `physical` (its nodes, into each); a point counted as skipped.
void add_msh_element(Fields& f, int count, long long id, const NodeIds& ids, ReadMesh& mesh,
                     const std::vector<long long>& physical,
                     std::map<long long, std::vector<std::array<int, 2>>>& lines,
                     const LineReader& reader) {
  if (count < 0) {
    ++mesh.num_skipped_elements;
    if (count == -2) {
      const int a = ids.at(f.integer("a node tag"), reader, id);
      const int b = ids.at(f.integer("a node tag"), reader, id);
      for (long long tag : physical) lines[tag].push_back({a, b});
    }
    return;
  }
  std::vector<int> nodes;
  for (int i = 0; i < count; ++i) nodes.push_back(ids.at(f.integer("a node tag"), reader, id));
  add_element(mesh, nodes, reader, id);
}

long long need_count(Fields& f, const char* what, const LineReader& reader) {
  const long long n = f.integer(what);
  if (n < 0) reader.fail(std::string(what) + " is negative");
  return n;
}

bool read_gr3_boundaries(LineReader& r, const NodeIds& ids, const std::string& kind,
                         const std::function<bool(long long)>& keep,
                         std::vector<std::vector<int>>& out);

// SCHISM's hgrid.gr3 / hgrid.ll and ADCIRC's fort.14: a title, "NE NP", NP lines
// "id x y depth", NE lines "id k n1 .. nk"; then, when the file goes on, the open
// boundaries: "NOPE", "NETA", and for each "n" and n lines of a node id; then the land
// boundaries, of which only the flux ones are kept (read_gr3_boundaries).
void read_gr3(LineReader& r, ReadMesh& mesh) {
  // The CRS that isoquad's title line names ("... CRS: EPSG:32630", or a PROJ string).
  const std::string title = r.need("a title line");
  const std::size_t crs_at = title.find(" CRS: ");
  if (mesh.format == "gr3" && crs_at != std::string::npos) {
    std::string crs = title.substr(crs_at + 6);
    while (!crs.empty() && std::isspace(static_cast<unsigned char>(crs.back()))) crs.pop_back();
    mesh.crs = crs;
  }
  const std::string counts = r.need("the numbers of elements and nodes");
  Fields f(counts, r);
  const long long ne = need_count(f, "the number of elements", r);
  const long long np = need_count(f, "the number of nodes", r);
  NodeIds ids;
  mesh.points.reserve(np);
  for (long long k = 0; k < np; ++k) {
    const std::string line = r.need("node " + std::to_string(k + 1) + " of " + std::to_string(np));
    Fields n(line, r);
    add_node(n, n.integer("a node id"), ids, mesh, r, true);
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
  if (!read_gr3_boundaries(
          r, ids, "open", [](long long) { return true; }, mesh.open_boundaries))
    return;  // the end: no boundaries
  // The land boundaries, when the file goes on. ADCIRC's flux boundaries (IBTYPE 2, 12,
  // 22, 32 or 52: a river's inflow) are open boundaries of the new mesh too; the others
  // (land, islands, barriers; SCHISM's 0 and 1) are the rest of the outline. The section
  // is not needed otherwise: where it cannot be read, a note says so and it is left.
  const std::size_t num_open = mesh.open_boundaries.size();
  try {
    read_gr3_boundaries(
        r, ids, "land",
        [](long long type) {
          return type == 2 || type == 12 || type == 22 || type == 32 || type == 52;
        },
        mesh.open_boundaries);
    mesh.num_flux_boundaries = mesh.open_boundaries.size() - num_open;
  } catch (const Error& e) {
    mesh.open_boundaries.resize(num_open);
    mesh.notes.push_back(e.message() +
                         ": its land boundaries are not read (a flux boundary "
                         "among them, a river's, would be land)");
  }
}

// A boundary section of a .gr3 or .14 (`kind`: "open" or "land"), when the file goes on:
// "N", "the total", and for each boundary "n [type]" and n lines starting with a node
// id. The boundaries whose type `keep` takes (0 when the line has none) go to `out` as
// node lists. False at the end of the file.
bool read_gr3_boundaries(LineReader& r, const NodeIds& ids, const std::string& kind,
                         const std::function<bool(long long)>& keep,
                         std::vector<std::vector<int>>& out) {
  std::string line;
  while (r.next(line) && line.find_first_not_of(" \t") == std::string::npos) {
  }
  if (line.find_first_not_of(" \t") == std::string::npos) return false;
  Fields f(line, r);
  const std::string plural = "the number of " + kind + " boundaries";
  const long long count = need_count(f, plural.c_str(), r);
  const std::string total = "the total number of " + kind + " boundary nodes";
  Fields t(r.need(total), r);
  need_count(t, total.c_str(), r);
  for (long long k = 0; k < count; ++k) {
    const std::string what = kind + " boundary " + std::to_string(k + 1);
    Fields c(r.need("the number of nodes of " + what), r);
    const std::string nodes = "the number of nodes of " + what;
    const long long n = need_count(c, nodes.c_str(), r);
    long long type = 0;
    if (!c.at_end()) {
      const std::string word = c.word("the boundary's type");
      if (std::from_chars(word.data(), word.data() + word.size(), type).ec != std::errc()) type = 0;
    }
    const bool kept = keep(type);
    std::vector<int> segment;
    for (long long i = 0; i < n; ++i) {
      Fields v(r.need("node " + std::to_string(i + 1) + " of " + what), r);
      const long long id = v.integer("a node id");
      if (!kept) continue;
      const int index = ids.find(id);
      if (index < 0)
        r.fail(what + " has node " + std::to_string(id) + ", which is not among the file's nodes");
      segment.push_back(index);
    }
    if (kept) out.push_back(std::move(segment));
  }
  return true;
}

// SMS's .2dm: cards ND (nodes), E3T and E4Q (elements), NS (nodestrings: node ids, the
// last negative, then perhaps the string's name, as BASEMENT writes it; one string may
// run over several cards), each nodestring a group of curves numbered from 1 in the
// file's order; the other cards (MESH2D, MESHNAME...) skipped, second-order elements
// refused.
void read_2dm(LineReader& r, ReadMesh& mesh) {
  NodeIds ids;
  struct Pending {
    long long id;
    std::vector<long long> nodes;
    int line;
  };
  std::vector<Pending> elements;  // nodes may follow the elements
  std::vector<Pending> strings;   // id: the string's number; its name in names
  std::vector<std::string> names;
  bool string_open = false;
  std::string line;
  while (r.next(line)) {
    Fields f(line, r);
    if (f.at_end()) continue;
    const std::string card = f.word("a card");
    if (card == "ND") {
      add_node(f, f.integer("a node id"), ids, mesh, r, true);
    } else if (card == "E3T" || card == "E4Q") {
      Pending p{f.integer("an element id"), {}, r.number()};
      for (int i = 0; i < (card == "E3T" ? 3 : 4); ++i) p.nodes.push_back(f.integer("a node id"));
      elements.push_back(std::move(p));
    } else if (card == "E6T" || card == "E8Q" || card == "E9Q" || card == "E2L" || card == "E3L") {
      r.fail("element card " + card + ": only E3T and E4Q (triangles and quadrangles) are read");
    } else if (card == "NS") {
      while (!f.at_end()) {
        if (!string_open) {
          strings.push_back({static_cast<long long>(strings.size()) + 1, {}, r.number()});
          names.emplace_back();
          string_open = true;
        }
        const long long id = f.integer("a node id of the nodestring");
        strings.back().nodes.push_back(std::abs(id));
        if (id < 0) {
          string_open = false;
          if (!f.at_end()) names.back() = f.word("the nodestring's name");
          break;
        }
      }
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
  for (std::size_t k = 0; k < strings.size(); ++k) {
    const Pending& p = strings[k];
    ReadMesh::CurveGroup group{p.id, names[k], {}};
    int previous = -1;
    for (long long id : p.nodes) {
      const int index = ids.find(id);
      if (index < 0)
        r.fail_at(p.line, "nodestring " + std::to_string(p.id) + " has node " + std::to_string(id) +
                              ", which is not among the ND cards");
      if (previous >= 0 && previous != index) group.edges.push_back({previous, index});
      previous = index;
    }
    mesh.curve_groups.push_back(std::move(group));
  }
  if (!mesh.curve_groups.empty()) open_boundaries_from_groups(mesh, {}, r.path());
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

// A .msh's $PhysicalNames: the names of the groups of curves (dimension 1) by tag.
void read_msh_names(LineReader& r, std::map<long long, std::string>& names) {
  Fields c(r.need("the number of physical names"), r);
  const long long n = need_count(c, "the number of physical names", r);
  for (long long k = 0; k < n; ++k) {
    Fields f(r.need("a physical name"), r);
    const long long dim = f.integer("a physical group's dimension");
    const long long tag = f.integer("a physical group's tag");
    std::string name = f.rest();
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
      name = name.substr(1, name.size() - 2);
    if (dim == 1) names[tag] = name;
  }
  if (r.need("$EndPhysicalNames") != "$EndPhysicalNames") r.fail("expected $EndPhysicalNames");
}

// A .msh 4.1's $Entities: the physical groups of each curve (the points', surfaces' and
// volumes' lines skipped).
void read_msh_entities(LineReader& r, std::map<long long, std::vector<long long>>& of_curve) {
  Fields c(r.need("the numbers of entities"), r);
  const long long points = need_count(c, "the number of points", r);
  const long long curves = need_count(c, "the number of curves", r);
  for (long long k = 0; k < points; ++k) r.need("a point entity");
  for (long long k = 0; k < curves; ++k) {
    Fields f(r.need("a curve entity"), r);
    const long long tag = f.integer("a curve's tag");
    for (int i = 0; i < 6; ++i) f.number("a curve's bounding box");
    const long long n = need_count(f, "a curve's number of physical tags", r);
    std::vector<long long>& groups = of_curve[tag];
    for (long long i = 0; i < n; ++i) groups.push_back(f.integer("a physical tag"));
  }
  std::string line;
  while (r.next(line))
    if (line == "$EndEntities") return;
  r.fail("no $EndEntities");
}

// Gmsh's .msh, ASCII, version 2.2 or 4.1 ($Nodes and $Elements; the physical groups of
// curves from $PhysicalNames, $Entities and the lines' tags; the other sections skipped).
void read_msh(LineReader& r, ReadMesh& mesh) {
  std::string line;
  double version = 0;
  NodeIds ids;
  bool has_nodes = false, has_elements = false;
  std::map<long long, std::string> names;
  std::map<long long, std::vector<long long>> of_curve;
  std::map<long long, std::vector<std::array<int, 2>>> lines;
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
    } else if (line == "$PhysicalNames") {
      read_msh_names(r, names);
    } else if (line == "$Entities" && version >= 4) {
      read_msh_entities(r, of_curve);
    } else if (line == "$Nodes") {
      if (version == 0) r.fail("$Nodes before $MeshFormat");
      has_nodes = true;
      if (version < 3) {
        Fields c(r.need("the number of nodes"), r);
        const long long n = need_count(c, "the number of nodes", r);
        for (long long k = 0; k < n; ++k) {
          Fields f(r.need("a node"), r);
          add_node(f, f.integer("a node tag"), ids, mesh, r);
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
            add_node(f, tags[k], ids, mesh, r);  // z and parametric ones ignored
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
        std::vector<long long> physical;
        for (long long k = 0; k < n; ++k) {
          Fields f(r.need("an element"), r);
          const long long id = f.integer("an element tag");
          const int count = msh_element_nodes(f.integer("the element type"), r);
          const long long tags = need_count(f, "the number of tags", r);
          physical.clear();
          for (long long t = 0; t < tags; ++t) {
            const long long tag = f.integer("a tag");
            if (t == 0 && tag != 0) physical.push_back(tag);  // the first: the physical group
          }
          add_msh_element(f, count, id, ids, mesh, physical, lines, r);
        }
      } else {
        Fields c(r.need("the elements' counts"), r);
        const long long blocks = need_count(c, "the number of entity blocks", r);
        const std::vector<long long> none;
        for (long long b = 0; b < blocks; ++b) {
          Fields h(r.need("an entity block of elements"), r);
          const long long dim = h.integer("the entity's dimension");
          const long long entity = h.integer("the entity's tag");
          const int count = msh_element_nodes(h.integer("the element type"), r);
          const long long n = need_count(h, "the block's number of elements", r);
          const auto it = dim == 1 ? of_curve.find(entity) : of_curve.end();
          const std::vector<long long>& physical = it == of_curve.end() ? none : it->second;
          for (long long k = 0; k < n; ++k) {
            Fields f(r.need("an element"), r);
            const long long id = f.integer("an element tag");
            add_msh_element(f, count, id, ids, mesh, physical, lines, r);
          }
        }
      }
      if (r.need("$EndElements") != "$EndElements") r.fail("expected $EndElements");
    }
  }
  if (version == 0) r.fail("no $MeshFormat section: not a Gmsh .msh file");
  if (!has_nodes || !has_elements) r.fail("no $Nodes or no $Elements section");
  for (auto& [tag, edges] : lines) {
    const auto name = names.find(tag);
    mesh.curve_groups.push_back(
        {tag, name == names.end() ? std::string() : name->second, std::move(edges)});
  }
  open_boundaries_from_groups(mesh, {}, r.path());
}

// Runs of boundary faces of one open kind along the outline's loops, as node lists (a
// whole loop repeats its first node) into mesh.open_boundaries: kind(a, b) is 0 where
// the face from node a to node b is land, else the open boundary's kind (a code, a
// group), so that two open boundaries that meet stay two. A mesh without an outline has
// none here (false): where the outline is needed, its error comes then.
bool open_runs(ReadMesh& mesh, const std::string& path,
               const std::function<long long(int, int)>& face_kind) {
  std::vector<std::vector<int>> loops;
  try {
    loops = mesh_outline(mesh.points, mesh.quads, mesh.triangles, path);
  } catch (const Error&) {
    return false;
  }
  for (const std::vector<int>& loop : loops) {
    const std::size_t n = loop.size();
    auto kind = [&](std::size_t i) { return face_kind(loop[i % n], loop[(i + 1) % n]); };
    // Start where the kind changes, so that no run wraps round the loop's start.
    std::size_t start = 0;
    while (start < n && kind(start) == kind(start + n - 1)) ++start;
    if (start == n) {  // one kind all round
      if (kind(0) == 0) continue;
      std::vector<int> whole = loop;
      whole.push_back(loop.front());
      mesh.open_boundaries.push_back(std::move(whole));
      continue;
    }
    for (std::size_t k = 0; k < n;) {
      const long long code = kind(start + k);
      std::size_t end = k;
      while (end < n && kind(start + end) == code) ++end;
      if (code != 0) {
        std::vector<int> run;
        for (std::size_t i = k; i <= end; ++i) run.push_back(loop[(start + i) % n]);
        mesh.open_boundaries.push_back(std::move(run));
      }
      k = end;
    }
  }
  return true;
}

// The open boundaries from the nodes' codes (0 inside, 1 land, 2, 3... open: a MIKE
// mesh's), by MIKE's rule: a boundary face is land when either end is, else open with
// its end node's code.
void open_boundaries_from_codes(const std::vector<long long>& codes, const std::string& path,
                                ReadMesh& mesh) {
  if (std::none_of(codes.begin(), codes.end(), [](long long c) { return c > 1; })) return;
  open_runs(mesh, path, [&](int a, int b) { return codes[a] > 1 && codes[b] > 1 ? codes[b] : 0; });
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
  std::vector<long long> codes;
  for (long long k = 0; k < np; ++k) {
    Fields f(r.need("node " + std::to_string(k + 1) + " of " + std::to_string(np)), r);
    add_node(f, f.integer("a node id"), ids, mesh, r, true);
    codes.push_back(f.at_end() ? 0 : f.integer("the node's boundary code"));
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
  open_boundaries_from_codes(codes, r.path(), mesh);
}

// A netCDF file open for reading; Error(input) naming the file for each failure.
class NcReader {
 public:
  explicit NcReader(const std::string& path) : path_(path) {
    const int status = nc_open(path.c_str(), NC_NOWRITE, &id_);
    if (status != NC_NOERR)
      throw Error(ErrorClass::input, "read",
                  "'" + path + "': not a netCDF file (" + nc_strerror(status) + ")");
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

// UGRID-1.0 (the first variable with cf_role mesh_topology and topology_dimension 2:
// its node coordinates and face_node_connectivity, numbered from start_index, with
// _FillValue or negative numbers for missing corners), or D-Flow FM's older net file
// (NetNode_x, NetNode_y, NetElemNode numbered from 1).
void read_netcdf(const std::string& path, ReadMesh& mesh) {
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
    if (bottom < 0 && i < counts[0] && (lower(name) == "bottom" || lower(name) == "fond"))
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

// A layer of polygons, each a triangle or a quadrangle (isoquad's GeoPackage layer
// `quads`, or elements exported as polygons): the layer `quads` when there is one, else
// the first of polygons; the nodes are the rings' vertices, the same where their
// coordinates are (so that two polygons that share a corner share the node); the CRS the
// layer's.
void read_polygon_layer(const std::string& path, ReadMesh& mesh) {
  const GdalDataset ds = open_vector_dataset(path, "read");
  OGRLayer* layer = ds->GetLayerByName("quads");
  for (int i = 0; i < ds->GetLayerCount() && !layer; ++i) {
    const OGRwkbGeometryType type = wkbFlatten(ds->GetLayer(i)->GetGeomType());
    if (type == wkbPolygon || type == wkbMultiPolygon) layer = ds->GetLayer(i);
  }
  auto fail = [&](const std::string& what) {
    throw Error(ErrorClass::input, "read", "'" + path + "': " + what);
  };
  if (!layer) fail("no layer of polygons (the quads or triangles of a mesh)");
  const std::string name = layer->GetName();
  if (const OGRSpatialReference* srs = layer->GetSpatialRef()) mesh.crs = crs_from_srs(*srs).wkt;
  std::map<std::pair<double, double>, int> nodes;
  std::vector<int> corners;
  layer->ResetReading();
  for (auto& feature : *layer) {
    const std::string which = "layer '" + name + "', feature " + std::to_string(feature->GetFID());
    const OGRGeometry* g = feature->GetGeometryRef();
    if (!g) fail(which + " has no geometry");
    if (const auto* multi = dynamic_cast<const OGRMultiPolygon*>(g)) {
      if (multi->getNumGeometries() != 1) fail(which + " is a multipolygon of several parts");
      g = multi->getGeometryRef(0);
    }
    const auto* polygon = dynamic_cast<const OGRPolygon*>(g);
    if (!polygon || !polygon->getExteriorRing()) fail(which + " is not a polygon");
    if (polygon->getNumInteriorRings() > 0) fail(which + " has a hole");
    const OGRLinearRing* ring = polygon->getExteriorRing();
    int n = ring->getNumPoints();
    if (n > 1 && ring->getX(0) == ring->getX(n - 1) && ring->getY(0) == ring->getY(n - 1)) --n;
    if (n != 3 && n != 4)
      fail(which + " has " + std::to_string(n) +
           " corners: only triangles and quadrangles are read");
    corners.clear();
    for (int i = 0; i < n; ++i) {
      const Point2 p{ring->getX(i), ring->getY(i)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        fail(which + " has a corner that is not finite");
      const auto [it, added] =
          nodes.emplace(std::make_pair(p.x, p.y), static_cast<int>(mesh.points.size()));
      if (added) mesh.points.push_back(p);
      corners.push_back(it->second);
    }
    for (std::size_t i = 0; i < corners.size(); ++i)
      for (std::size_t j = i + 1; j < corners.size(); ++j)
        if (corners[i] == corners[j]) fail(which + " has the same corner twice");
    if (n == 3)
      mesh.triangles.push_back({corners[0], corners[1], corners[2]});
    else
      mesh.quads.push_back({corners[0], corners[1], corners[2], corners[3]});
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
  if (ext == ".nc") return "nc";
  if (ext == ".slf" || ext == ".srf") return "slf";
  if (ext == ".gpkg" || ext == ".shp" || ext == ".geojson" || ext == ".fgb") return "polygons";
  throw Error(ErrorClass::usage, "options",
              "'" + path +
                  "': a mesh to measure is a .gr3 or .ll (SCHISM), .14 or .grd (ADCIRC), .2dm "
                  "(SMS), .msh (Gmsh, ASCII), .mesh (MIKE 21/3 FM), .nc (UGRID, D-Flow FM's net "
                  "file), .slf (TELEMAC's Selafin) or a layer of polygons, each a triangle or a "
                  "quadrangle (.gpkg: isoquad's layer 'quads', .shp, .geojson, .fgb)");
}

bool is_mesh_file(const std::string& path) {
  std::string format;
  try {
    format = mesh_file_format(path);
  } catch (const Error&) {
    return false;
  }
  if (format != "nc") return format != "polygons";
  // A netCDF file is a mesh when it holds one (UGRID's 2D mesh topology, or a D-Flow FM
  // net file's nodes); otherwise a grid, as GEBCO's and ETOPO's are, for GDAL to read as
  // a raster. One that netCDF cannot open is left to the mesh reader's message.
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

namespace {

std::string describe(const ReadMesh::CurveGroup& g) {
  return std::to_string(g.tag) + (g.name.empty() ? "" : " \"" + g.name + "\"");
}

}  // namespace

std::string curve_groups_kind(const ReadMesh& mesh, bool plural) {
  if (mesh.format == "2dm") return plural ? "nodestrings" : "nodestring";
  return plural ? "physical groups of curves" : "physical group of curves";
}

std::string curve_groups_text(const ReadMesh& mesh) {
  constexpr std::size_t kShown = 10;
  std::string text;
  for (std::size_t k = 0; k < mesh.curve_groups.size() && k < kShown; ++k)
    text += (text.empty() ? "" : ", ") + describe(mesh.curve_groups[k]);
  if (mesh.curve_groups.size() > kShown)
    text += "... (" + std::to_string(mesh.curve_groups.size()) + " in all)";
  return text;
}

void open_boundaries_from_groups(ReadMesh& mesh, const std::vector<std::string>& groups,
                                 const std::string& path) {
  if (mesh.format != "msh" && mesh.format != "2dm")
    throw Error(ErrorClass::usage, "read",
                "'" + path +
                    "' is neither a Gmsh .msh nor an SMS .2dm: only these name lines of the "
                    "boundary (physical groups of curves, nodestrings)");
  const std::string kind_name = curve_groups_kind(mesh, false);
  std::vector<const ReadMesh::CurveGroup*> open;
  if (groups.empty()) {
    for (const ReadMesh::CurveGroup& g : mesh.curve_groups)
      if (lower(g.name).rfind("open", 0) == 0) open.push_back(&g);
  }
  for (const std::string& given : groups) {
    const auto it = std::find_if(mesh.curve_groups.begin(), mesh.curve_groups.end(),
                                 [&](const ReadMesh::CurveGroup& g) {
                                   return g.name == given || std::to_string(g.tag) == given;
                                 });
    if (it == mesh.curve_groups.end()) {
      const std::string there = curve_groups_text(mesh);
      throw Error(ErrorClass::usage, "read",
                  "'" + path + "' has no " + kind_name + " '" + given + "' (" +
                      (there.empty() ? "it has none" : "it has " + there) + ")");
    }
    open.push_back(&*it);
  }
  mesh.open_boundaries.clear();
  if (open.empty()) return;
  // Each face of the outline's open kind: the index of its group among those open, + 1.
  std::map<std::pair<int, int>, long long> kind;
  for (std::size_t k = 0; k < open.size(); ++k)
    for (const auto& e : open[k]->edges)
      kind.emplace(std::minmax(e[0], e[1]), static_cast<long long>(k) + 1);
  std::vector<bool> on_outline(open.size(), false);
  const bool traced = open_runs(mesh, path, [&](int a, int b) -> long long {
    const auto it = kind.find(std::minmax(a, b));
    if (it == kind.end()) return 0;
    on_outline[it->second - 1] = true;
    return it->second;
  });
  if (groups.empty() || !traced) return;
  for (std::size_t k = 0; k < open.size(); ++k)
    if (!on_outline[k])
      throw Error(ErrorClass::usage, "read",
                  "'" + path + "': no line of " + kind_name + " " + describe(*open[k]) +
                      " lies on the mesh's outline, where an open boundary is");
}

ReadMesh read_mesh(const std::string& path) {
  ReadMesh mesh;
  mesh.format = mesh_file_format(path);
  if (!std::filesystem::is_regular_file(path))
    throw Error(ErrorClass::input, "read", "'" + path + "': no such mesh file");
  if (mesh.format == "nc") {
    read_netcdf(path, mesh);
  } else if (mesh.format == "slf") {
    read_selafin(path, mesh);
    read_telemac_cli(path, mesh);
  } else if (mesh.format == "polygons") {
    read_polygon_layer(path, mesh);
  } else {
    LineReader r(path);
    if (mesh.format == "gr3" || mesh.format == "14")
      read_gr3(r, mesh);
    else if (mesh.format == "2dm")
      read_2dm(r, mesh);
    else if (mesh.format == "msh")
      read_msh(r, mesh);
    else
      read_mike(r, mesh);
  }
  if (mesh.quads.empty() && mesh.triangles.empty())
    throw Error(ErrorClass::input, "read",
                "'" + path + "': the mesh has no triangle or quadrangle");
  if (std::any_of(mesh.node_values.begin(), mesh.node_values.end(),
                  [](double v) { return std::isnan(v); }))
    mesh.node_values.clear();
  // SCHISM's hgrid.ll is hgrid.gr3 in longitudes and latitudes.
  if (lower(std::filesystem::path(path).extension().string()) == ".ll") mesh.crs = "EPSG:4326";
  return mesh;
}

}  // namespace isoquad
