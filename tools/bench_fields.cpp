// Benchmarks on mainland France (Natural Earth 1:10m) with automatic sizing at about
// 4,500 quads: the front end, the background mesh and fields, the four tiling steps, and
// the whole mesh job; and the simplification of its coast drawn finely. Not a test: run it by hand,
// in a Release build, and compare stages as ratios within one run.
//   build/isoquad_bench_fields --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "app/fields_job.h"
#include "app/mesh_job.h"
#include "domain/simplify_domain.h"
#include "mesh/boundary_corners.h"
#include "tiling/build_tiling.h"

namespace {

using namespace isoquad;

FieldsOptions france_options() {
  FieldsOptions o;
  o.front.read.path = std::string(ISOQUAD_SOURCE_DIR) + "/shapefiles/france.shp";
  o.sizing.hmax_m = 28000.0;  // about 4,500 quads with the default gradation 0.2
  return o;
}

const Domain& france_domain() {
  static const FieldsResult front = [] {
    FieldsResult r;
    FieldsOptions o = france_options();
    // The simplification the mesh job applies: its automatic hmin, hmax / 10.
    const double hmin = o.sizing.hmax_m / 10.0;
    o.front.target_size_for_domain = [hmin](const Domain&, const MapScale*) { return hmin; };
    r.front = build_planar_domain(o.front);
    return r;
  }();
  return front.front.domain;
}

void BM_FranceFields(benchmark::State& state) {
  const Domain& domain = france_domain();
  const FieldsOptions options = france_options();
  double quads = 0, vertices = 0;
  for (auto _ : state) {
    FieldsResult r;
    build_fields_on_domain(domain, options, r);
    quads = predicted_num_quads(r.mesh, r.size);
    vertices = static_cast<double>(r.mesh.points.size());
    for (const StageTime& t : r.times) state.counters[t.stage] = t.seconds;
  }
  state.counters["predicted_quads"] = quads;
  state.counters["background_vertices"] = vertices;
}
BENCHMARK(BM_FranceFields)->Unit(benchmark::kMillisecond)->Iterations(1);

// The tiling steps (2.2 to 2.5 and the re-splitting of pairs) on the fields of
// BM_FranceFields.
void BM_FranceTiling(benchmark::State& state) {
  FieldsResult fields;
  build_fields_on_domain(france_domain(), france_options(), fields);
  double share_quads = 0, tiles = 0;
  for (auto _ : state) {
    BackgroundMesh mesh = fields.mesh;  // the repairs may clear corner tags
    tag_corners(mesh, fields.size, CornerParams());
    const TilingResult r = build_tiling(mesh, fields.size, fields.cross, TilingParams());
    for (const TilingStepReport& s : r.steps) state.counters[s.step] = s.seconds;
    share_quads = r.steps.back().stats.share_quads;
    tiles = r.steps.back().stats.num_tiles;
  }
  state.counters["share_quads"] = share_quads;
  state.counters["tiles"] = tiles;
}
BENCHMARK(BM_FranceTiling)->Unit(benchmark::kMillisecond)->Iterations(1);

// The whole job without writing: read, fields, tiling, subdivision, smoothing, quality.
void BM_FranceMesh(benchmark::State& state) {
  MeshOptions o;
  o.fields = france_options();
  double quads = 0, attempts = 0;
  for (auto _ : state) {
    const MeshResult r = build_mesh(o);
    quads = static_cast<double>(r.quads.quads.size());
    attempts = r.attempts;
  }
  state.counters["quads"] = quads;
  state.counters["attempts"] = attempts;
}
BENCHMARK(BM_FranceMesh)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_FranceDomain(benchmark::State& state) {
  FrontEndOptions o;
  o.read.path = std::string(ISOQUAD_SOURCE_DIR) + "/shapefiles/france.shp";
  o.simplify_m = 1000.0;
  for (auto _ : state) benchmark::DoNotOptimize(build_planar_domain(o));
}
BENCHMARK(BM_FranceDomain)->Unit(benchmark::kMillisecond);

// The simplification of a coastline drawn finely: France's domain with a vertex every
// `spacing` metres along its edges (the argument), simplified at 700 m with the clearance
// of the same (France automatic's). The time should grow with the vertices, not their
// square (docs/measurements.md, "Coastlines drawn finely").
void BM_DenseCoastSimplify(benchmark::State& state) {
  const double spacing = static_cast<double>(state.range(0));
  Domain dense = france_domain();
  for (Polygon& p : dense.polygons) {
    std::vector<Ring*> rings{&p.outer};
    for (Ring& h : p.holes) rings.push_back(&h);
    for (Ring* r : rings) {
      Ring out;
      for (std::size_t i = 0; i < r->size(); ++i) {
        const Point2 a = (*r)[i], b = (*r)[(i + 1) % r->size()];
        const int n = std::max(1, static_cast<int>(distance(a, b) / spacing));
        for (int k = 0; k < n; ++k)
          out.push_back({a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n});
      }
      *r = std::move(out);
    }
  }
  double before = 0, after = 0;
  for (auto _ : state) {
    Domain d = dense;
    const SimplifyResult r = simplify_domain(d, {700.0, 700.0});
    before = static_cast<double>(r.num_vertices_before);
    after = static_cast<double>(r.num_vertices_after);
  }
  state.counters["vertices_before"] = before;
  state.counters["vertices_after"] = after;
}
BENCHMARK(BM_DenseCoastSimplify)
    ->Arg(160)
    ->Arg(80)
    ->Arg(40)
    ->Arg(20)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
