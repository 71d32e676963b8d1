// The text formats of read_mesh: SCHISM's .gr3/.ll, ADCIRC's .14, SMS's .2dm, Gmsh's .msh
// and MIKE 21/3 FM's .mesh.
#include <algorithm>
#include <limits>
#include <map>
#include <unordered_map>

#include "core/error.h"
#include "core/text.h"
#include "gis/read_mesh_formats.h"

namespace isoquad::mesh_readers {

namespace {

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
  if (nodes.size() == 3) {
    mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
    mesh.triangle_ids.push_back(id);
  } else {
    mesh.quads.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
    mesh.quad_ids.push_back(id);
  }
}

// A node: its id (read before) and the line's next two numbers, x and y, and with
// `value` the third one when the line has it (a depth, or z), else NaN (the rest of the
// line ignored).
void add_node(Fields& f, long long id, NodeIds& ids, ReadMesh& mesh, const LineReader& reader,
              bool value = false) {
  ids.add(id, reader);
  const double x = f.number("x");
  mesh.points.push_back({x, f.number("y")});
  mesh.point_ids.push_back(id);
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

}  // namespace

// SCHISM's hgrid.gr3 / hgrid.ll and ADCIRC's fort.14: a title, "NE NP", NP lines
// "id x y depth", NE lines "id k n1 .. nk"; then, when the file goes on, the open
// boundaries: "NOPE", "NETA", and for each "n" and n lines of a node id; then the land
// boundaries, of which only the flux ones are kept (read_gr3_boundaries).
void read_gr3(LineReader& r, ReadMesh& mesh) {
  // The CRS that isoquad's title line names ("... CRS: EPSG:32630", or a PROJ string).
  const std::string title = r.need("a title line");
  const std::size_t crs_at = title.find(" CRS: ");
  if ((mesh.format == "gr3" || mesh.format == "14") && crs_at != std::string::npos) {
    std::string crs = title.substr(crs_at + 6);
    while (!crs.empty() && std::isspace(static_cast<unsigned char>(crs.back()))) crs.pop_back();
    mesh.crs = crs;
  }
  const std::string counts = r.need("the numbers of elements and nodes");
  Fields f(counts, r);
  const long long ne = need_count(f, "the number of elements", r);
  const long long np = need_count(f, "the number of nodes", r);
  NodeIds ids;
  // The count is the file's word: a damaged one must not reserve gigabytes.
  mesh.points.reserve(static_cast<std::size_t>(std::min<long long>(np, 1 << 20)));
  for (long long k = 0; k < np; ++k) {
    const std::string line = r.need("node " + std::to_string(k + 1) + " of " + std::to_string(np));
    Fields n(line, r);
    add_node(n, n.integer("a node id"), ids, mesh, r, true);
  }
  std::vector<int> nodes;
  for (long long k = 0; k < ne; ++k) {
    const std::string line =
        r.need("element " + std::to_string(k + 1) + " of " + std::to_string(ne));
    try {
      Fields e(line, r);
      const long long id = e.integer("an element id");
      const long long kind = e.integer("the element's number of nodes");
      if (kind != 3 && kind != 4)
        r.fail("element " + std::to_string(id) + " has " + std::to_string(kind) +
               " nodes: only triangles (3) and quadrangles (4) are read");
      nodes.clear();
      for (long long i = 0; i < kind; ++i) nodes.push_back(ids.at(e.integer("a node id"), r, id));
      add_element(mesh, nodes, r, id);
    } catch (const Error& e) {
      // The open boundaries' first line where an element should be: the header counts
      // more elements than the file has.
      if (k == 0 || line.find('=') == std::string::npos) throw;
      throw Error(e.error_class(), e.stage(),
                  e.message() + " (the header counts " + std::to_string(ne) +
                      " elements, and the file's elements seem to end after " + std::to_string(k) +
                      ": does the header count more than it has?)");
    }
  }
  // The open boundaries begin where the header's counts say the elements end: a header
  // that counts fewer elements or nodes than the file has makes them start too early.
  bool more = false;
  try {
    more = read_gr3_boundaries(
        r, ids, "open", [](long long) { return true; }, mesh.open_boundaries);
  } catch (const Error& e) {
    // Cut in the middle of a line: said so already.
    if (e.message().find("in the middle of a line") != std::string::npos) throw;
    // Ended early: cut short, or elements read as the boundaries.
    const bool ended = e.message().find("the file ends at line") != std::string::npos;
    throw Error(e.error_class(), e.stage(),
                e.message() + " (the open boundaries begin after the header's " +
                    std::to_string(ne) + " elements and " + std::to_string(np) + " nodes: " +
                    (ended ? "is the file cut short, or does it have more than its header "
                             "counts?)"
                           : "does the file have more than its header counts?)"));
  }
  if (!more) return;  // the end: no boundaries
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

namespace {

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

}  // namespace

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
          std::vector<long long> tags;  // grown as read: n is the file's word
          for (long long k = 0; k < n; ++k) {
            Fields t(r.need("a node tag"), r);
            tags.push_back(t.integer("a node tag"));
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

}  // namespace isoquad::mesh_readers
