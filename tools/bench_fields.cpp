// Benchmark of the background mesh and fields on mainland France (Natural Earth 1:10m)
// with automatic sizing at about 4,500 quads. Not a test: run it by hand, in a Release
// build, and compare stages as ratios within one run.
//   build/isoquad_bench_fields --benchmark_repetitions=3
#include <benchmark/benchmark.h>

#include "app/fields_job.h"

namespace {

using namespace isoquad;

FieldsOptions france_options() {
  FieldsOptions o;
  o.front.read.path = std::string(ISOQUAD_SOURCE_DIR) + "/shapefiles/france.shp";
  o.sizing.hmax_m = 14500.0;  // about 4,500 quads (see the summary's prediction)
  return o;
}

const Domain& france_domain() {
  static const FieldsResult front = [] {
    FieldsResult r;
    FieldsOptions o = france_options();
    o.front.target_size_for_area = [](double) { return 1450.0; };
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

void BM_FranceDomain(benchmark::State& state) {
  FrontEndOptions o;
  o.read.path = std::string(ISOQUAD_SOURCE_DIR) + "/shapefiles/france.shp";
  o.simplify_m = 1000.0;
  for (auto _ : state) benchmark::DoNotOptimize(build_planar_domain(o));
}
BENCHMARK(BM_FranceDomain)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
