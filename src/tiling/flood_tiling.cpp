#include "tiling/flood_tiling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

namespace isoquad {

namespace {

// Non-negative floats order like their bit patterns: the key goes in the high word so
// that the heap compares plain integers, the triangle id breaking ties.
std::uint64_t pack(float key, int f) {
  std::uint32_t bits;
  std::memcpy(&bits, &key, sizeof bits);
  return (static_cast<std::uint64_t>(bits) << 32) | static_cast<std::uint32_t>(f);
}

constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace

LinfFlood::LinfFlood(const BackgroundMesh& mesh, const TriangleGeometry& geom,
                     const CrossField& cross)
    : mesh_(mesh), geom_(geom), cross_(cross) {
  const int num_faces = geom.num_triangles();
  best_key_.assign(num_faces, kInfinity);
  best_tile_.assign(num_faces, -1);
  stamp_.assign(num_faces, 0);
}

void LinfFlood::set_frame(int tile, int generator) {
  gx_[tile] = geom_.cx[generator];
  gy_[tile] = geom_.cy[generator];
  const double a = frame_angle_at(mesh_, cross_, generator);
  cu_[tile] = std::cos(a);
  su_[tile] = std::sin(a);
  inv_h_[tile] = 1.0 / geom_.size_m[generator];
}

float LinfFlood::key(int tile, int f) const {
  const double dx = geom_.cx[f] - gx_[tile], dy = geom_.cy[f] - gy_[tile];
  const double c = cu_[tile], s = su_[tile];
  // The size between generator and triangle: the mean of both ends, so that a tile of a
  // large generator stops where the sizing asks for small tiles.
  const double h = 0.5 * (1.0 / inv_h_[tile] + geom_.size_m[f]);
  return static_cast<float>(std::max(std::abs(dx * c + dy * s), std::abs(dy * c - dx * s)) / h);
}

void LinfFlood::offer(int tile, int f) {
  const float k = key(tile, f);
  if (k < best_key_[f] || (k == best_key_[f] && tile < best_tile_[f])) {
    const bool same_entry = k == best_key_[f];
    best_key_[f] = k;
    best_tile_[f] = tile;
    if (!same_entry) {
      heap_.push_back(pack(k, f));
      std::push_heap(heap_.begin(), heap_.end(), std::greater<std::uint64_t>());
    }
  }
}

void LinfFlood::run(std::vector<int>& label) {
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<std::uint64_t>());
    const int f = static_cast<int>(heap_.back() & 0xffffffffu);
    heap_.pop_back();
    if (label[f] >= 0) continue;  // reached earlier with a smaller key
    const int tile = best_tile_[f];
    label[f] = tile;
    ++num_flooded_;
    for (int i = 0; i < 3; ++i) {
      const int g = mesh_.neighbours[f][i];
      if (g >= 0 && label[g] < 0 && !geom_.crosses_barrier(f, i)) offer(tile, g);
    }
  }
}

void LinfFlood::flood(const std::vector<int>& generator, std::vector<int>& label) {
  const int num_tiles = static_cast<int>(generator.size());
  const int num_faces = geom_.num_triangles();
  gx_.assign(num_tiles, 0.0);
  gy_.assign(num_tiles, 0.0);
  cu_.assign(num_tiles, 1.0);
  su_.assign(num_tiles, 0.0);
  inv_h_.assign(num_tiles, 1.0);
  generator_ = generator;
  label.assign(num_faces, -1);
  std::fill(best_key_.begin(), best_key_.end(), kInfinity);
  std::fill(best_tile_.begin(), best_tile_.end(), -1);
  heap_.clear();
  num_flooded_ = 0;
  for (int t = 0; t < num_tiles; ++t) {
    const int g = generator[t];
    set_frame(t, g);
    offer(t, g);
  }
  run(label);
}

void LinfFlood::reflood(const std::vector<int>& generator, std::vector<int>& label,
                        std::vector<char>& changed) {
  const int num_tiles = static_cast<int>(generator.size());
  changed.assign(num_tiles, 0);
  if (static_cast<int>(generator_.size()) != num_tiles) {
    flood(generator, label);
    changed.assign(num_tiles, 1);
    return;
  }
  // The region: every tile whose generator moved, and the tiles next to it. Tiles are
  // connected and own their previous generator, so a search from it finds them.
  ++current_stamp_;
  const int stamp = current_stamp_;
  region_.clear();
  auto collect = [&](int tile, bool mark_neighbours) {
    const int start = generator_[tile];
    stamp_[start] = stamp;
    stack_.assign(1, start);
    while (!stack_.empty()) {
      const int f = stack_.back();
      stack_.pop_back();
      region_.push_back(f);
      for (int g : mesh_.neighbours[f]) {
        if (g < 0) continue;
        if (label[g] == tile) {
          if (stamp_[g] != stamp) {
            stamp_[g] = stamp;
            stack_.push_back(g);
          }
        } else if (mark_neighbours && !changed[label[g]]) {
          changed[label[g]] = 2;  // a neighbour, collected below
        }
      }
    }
  };
  bool any = false;
  for (int t = 0; t < num_tiles; ++t) {
    if (generator[t] == generator_[t]) continue;
    changed[t] = 1;
    any = true;
  }
  num_flooded_ = 0;
  if (!any) return;
  for (int t = 0; t < num_tiles; ++t)
    if (changed[t] == 1) collect(t, true);
  for (int t = 0; t < num_tiles; ++t)
    if (changed[t] == 2) collect(t, false);

  for (int f : region_) {
    label[f] = -1;
    best_key_[f] = kInfinity;
    best_tile_[f] = -1;
  }
  heap_.clear();
  for (int t = 0; t < num_tiles; ++t) {
    if (!changed[t]) continue;
    const int g = generator[t];
    if (label[g] >= 0) {  // a generator outside the region: start over
      flood(generator, label);
      changed.assign(num_tiles, 1);
      return;
    }
    if (g != generator_[t]) set_frame(t, g);
    offer(t, g);
  }
  // The tiles around the region compete for it from its rim.
  for (int f : region_)
    for (int i = 0; i < 3; ++i) {
      const int g = mesh_.neighbours[f][i];
      if (g >= 0 && label[g] >= 0 && !geom_.crosses_barrier(f, i)) offer(label[g], f);
    }
  generator_ = generator;
  run(label);
  for (int f : region_) changed[label[f]] = 1;
  for (char& c : changed) c = c ? 1 : 0;
}

}  // namespace isoquad
