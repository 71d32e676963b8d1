// The outline of a mesh read from a file (triangles and quadrangles): its boundary
// edges, the sides of one element each, as closed loops. `isoquad quality` without
// INPUT measures a mesh against the fields of this domain, the mesh's own.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "gis/read_mesh.h"
#include "gis/read_polygons.h"

namespace isoquad {

// Closed loops of node ids (first not repeated), domain on the left: outer loops
// counter-clockwise, holes clockwise, whichever way the elements run (as most of them
// do). Every loop is simple: where the boundary passes a node twice (two parts of the
// mesh, two holes, or a hole and the outer boundary touching at a node), the loops touch
// there. Loops are traced from the nodes in the order of their ids. `name` (the
// file) starts the messages of Error(input), thrown for a side of three or more
// elements, for elements whose orientations disagree along the boundary, and for a mesh
// without elements. The messages number the nodes as `point_ids` does (the file's own
// numbers, ReadMesh::point_ids; empty: from 1 in order).
std::vector<std::vector<int>> mesh_outline(const std::vector<Point2>& points,
                                           const std::vector<std::array<int, 4>>& quads,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::string& name,
                                           const std::vector<long long>& point_ids = {});

// What a mesh file gets wrong that its figures do not show, for `isoquad quality`'s
// warnings. Nodes and elements are named by the file's numbers (ReadMesh::point_ids,
// quad_ids, triangle_ids; file_number).
struct MeshDefects {
  std::size_t num_unused_nodes = 0;  // in no element
  long long first_unused = 0;
  // Nodes within `coincident_tolerance` (a billionth of the mesh's extent) of an earlier
  // node: elements on either side are not joined there (a crack, nodes left unmerged).
  std::size_t num_coincident_nodes = 0;
  std::array<long long, 2> first_coincident{};
  double coincident_tolerance = 0.0;
  // Elements on the same nodes as an earlier one ("quad 9 (as quad 2)").
  std::size_t num_duplicate_elements = 0;
  std::string first_duplicate;
  // Sides of three or more elements: an element given twice, or elements overlapping.
  std::size_t num_overused_sides = 0;
  std::array<long long, 2> first_overused{};
  // Elements that run round the other way from most (clockwise among counter-clockwise
  // ones, or the reverse: listed so, or folded), and the first of them ("quad 7",
  // "triangle 12").
  std::size_t num_reversed = 0, num_elements = 0;
  std::string first_reversed;
  // Elements without area (flat) or quads whose opposite sides cross (bow-ties).
  std::size_t num_degenerate = 0;
  std::string first_degenerate;
};
MeshDefects find_mesh_defects(const ReadMesh& mesh);
// The defects as warnings (none when it has none).
std::vector<std::string> mesh_defect_warnings(const MeshDefects& d);

// A mesh as the polygons of a domain: its outline's loops nested into polygons with
// holes by containment (rings_from_lines), in the CRS `crs_text` gives (as `option`,
// for messages) or else the file's own; layer "its outline", a feature per loop.
// Error(crs) when neither says the CRS, Error(input) as mesh_outline, or for loops that
// do not nest. A mesh in longitudes with elements across the cut of its longitudes (a
// grid round the globe, or one across the antimeridian in [-180, 180)) has no outline in
// them: its nodes are first projected into the automatic projection of a domain of them
// (choose_local_projection), the outline's CRS then. `nodes`, when given, receives the
// mesh's nodes in the outline's CRS.
SourceData outline_source(const ReadMesh& mesh, const std::string& path,
                          const std::string& crs_text, const std::string& option,
                          std::vector<Point2>* nodes = nullptr);

}  // namespace isoquad
