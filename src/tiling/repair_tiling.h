// Restores the invariants of a tiling (check_tiling, meta_graph.h) after a step that
// may break them: flooding and merging produce connected tiles, but a tile can wrap an
// island or another tile, touch itself at a vertex, end up with fewer than 3
// meta-vertices, or cover a reflex corner of the domain alone (its quad there could not
// be convex).
#pragma once

#include "mesh/background_mesh.h"
#include "tiling/meta_graph.h"
#include "tiling/tile_geometry.h"
#include "tiling/tiling.h"

namespace isoquad {

struct RepairParams {
  MetaGraphParams graph;
  // Reflex corners sharper than this (turning angle below minus this) ask for three tiles
  // (quad angles of at most 110 degrees there) instead of two; best effort.
  double sharp_reflex_deg = 120.0;
  // At a reflex corner in one tile, the tile is split in two there; a part lighter than
  // this (in ideal tiles, mass) joins a neighbouring tile instead of becoming a tile.
  double max_merged_part_mass = 0.5;
  // A reflex corner whose split the other repairs undid this many times loses its corner
  // tag (demote_corner).
  int max_corner_splits = 4;
  int max_rounds = 200;
  // Checks every round's structures, brought up to date from the tiles a fix changed,
  // against those found again from all the labels (slow; for tests). A difference is an
  // internal error.
  bool verify_updates = false;
};

struct RepairStats {
  int fragments_merged = 0;    // disconnected parts merged into a neighbouring tile
  int enclosed_merged = 0;     // tiles enclosed by one tile, merged into it
  int rings_cut = 0;           // tiles wrapping an island or a large enclosed region, cut open
  int pinches_split = 0;       // tiles touching themselves at a vertex
  int small_tiles_merged = 0;  // tiles with fewer than 3 meta-vertices
  int tiles_split = 0;         // tiles split (at reflex corners, or isolated small tiles)
  int corners_demoted = 0;     // reflex corners whose tag was cleared (see RepairParams)
  int corners_added = 0;       // islands of about one tile given four corners
  int rounds = 0;
  int rounds_updated = 0;  // rounds whose structures were updated from the last fix
  int total() const {
    return fragments_merged + enclosed_merged + rings_cut + pinches_split + small_tiles_merged +
           tiles_split;
  }
};

// Repairs in rounds, one kind of violation per round in the order above, until
// check_tiling passes. The first round finds the tiles' fragments, boundaries and vertex
// sectors from all the labels; later rounds update them round the tiles the last fix
// changed (the same structures, at a fraction of the cost). Tile ids are renumbered when tiles
// disappear (surviving tiles keep their order); tiles whose triangles changed get the relocated
// generator (2.3), others keep theirs. Throws Error(meshing) when the invariants still fail after
// max_rounds. The mesh's corner tags may be cleared (RepairParams::max_corner_splits). With
// `graph`, also gives the meta-graph of the repaired tiling (built for the final check anyway).
RepairStats repair_tiling(BackgroundMesh& mesh, const TriangleGeometry& geom,
                          Tiling& tiling, const RepairParams& params = RepairParams(),
                          MetaGraph* graph = nullptr);

}  // namespace isoquad
