// explore's cost per width point: one model evaluation of a 512x512 scene
// (bench/scenes/specular_512.json, ~65k shaded pixels) at a new width point, with the host setup
// (projection, Taylor setup, visibility, reference image) done once and reused, as explore does.
// Target: <= 50 ms per point on one core (Google Benchmark runs the loop on one thread).
//   ExplorePoint:     re-encode (quantize the coefficients), the bit-accurate model, the
//                     comparison with the reference, the cycle model; a different series and
//                     coefficient width every iteration, so no point repeats.
//   ExploreHostSetup: the once-per-scene part, for comparison.
#include <benchmark/benchmark.h>

#include "derive/derive_config.h"
#include "explore/explore.h"

namespace shadesim {
namespace {

const char* const kScene = SHADESIM_SOURCE_DIR "/bench/scenes/specular_512.json";

const UnitConfig& start() {
  static const UnitConfig c = derive_config({kScene}, DeriveOptions{}).config;
  return c;
}

ExploreScenes& scenes() {
  static ExploreScenes s({kScene}, start(), std::nullopt, 12);
  return s;
}

void BM_ExplorePoint(benchmark::State& state) {
  ExploreScenes& s = scenes();
  const UnitConfig& base = start();
  int i = 0;
  uint64_t pixels = 0;
  for (auto _ : state) {
    UnitConfig c = base;
    c.series.wl = c.series.iwl + 12 + i % 9;    // series fraction 12..20
    c.coef.wl = c.coef.iwl + 12 + (i / 9) % 9;  // coefficient fraction 12..20
    ++i;
    const PointFigures p = evaluate_point(s, c, AreaFunction{});
    pixels = p.pixels;
    benchmark::DoNotOptimize(p.error.max_code_lsb);
  }
  state.counters["pixels"] = static_cast<double>(pixels);
}
BENCHMARK(BM_ExplorePoint)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_ExploreHostSetup(benchmark::State& state) {
  for (auto _ : state) {
    ExploreScenes s({kScene}, start(), std::nullopt, 12);
    benchmark::DoNotOptimize(&s);
  }
}
BENCHMARK(BM_ExploreHostSetup)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace shadesim

BENCHMARK_MAIN();
