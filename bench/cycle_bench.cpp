// Cycle estimation speed on one stream, host setup excluded (the stream is prepared once):
//   CycleEstimate:  the closed form (model/cycle_estimate.h): cycles, scanlines, per triangle
//   CycleEstimateWithBreakdown: the same and the breakdown (what `shadesim cycles` runs)
//   CycleModel:     the clocked model, clock by clock (model/cycle_model.h)
// both with no gaps and no back-pressure.
//   CycleModelUnit/<structure>: the clocked model on one control structure each - a span queue on
//     a 4-word port, 4 pixel lanes, two material buffers (material_switch, a MATERIAL per few
//     triangles), host span setup - so each control module's path is timed on its own.
// The stream is bench/scenes/sphere_1024.json on its own
// configuration (derive_config), or the saved stream named by SHADESIM_CYCLE_BENCH_STREAM (text
// form, its header names the unit): scripts/bench-cycles passes the one it co-simulates, so the
// ratio against co-simulation is on the same words.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "derive/derive_config.h"
#include "host/frame.h"
#include "model/command_stream.h"
#include "model/cycle_estimate.h"
#include "model/cycle_model.h"
#include "sim/harness/cycle_run.h"

namespace shadesim {
namespace {

struct BenchStream {
  UnitConfig config;
  std::vector<uint64_t> words;
};

const BenchStream& stream() {
  static const BenchStream s = [] {
    BenchStream b;
    if (const char* path = std::getenv("SHADESIM_CYCLE_BENCH_STREAM")) {
      const CommandStream cs = CommandStream::load(path);
      b.config = cs.config;
      b.words = cs.encode();
      return b;
    }
    const std::string scene = SHADESIM_SOURCE_DIR "/bench/scenes/sphere_1024.json";
    FrameOptions o;
    o.base = derive_config({scene}, DeriveOptions{}).config;
    o.fixed_unit = true;
    const PreparedFrame f = prepare_frame(scene, o);
    b.config = f.config;
    b.words = f.encoded.stream.encode();
    return b;
  }();
  return s;
}

void report(benchmark::State& state, uint64_t cycles) {
  const BenchStream& s = stream();
  state.SetItemsProcessed(
      static_cast<int64_t>(state.iterations() * cycles));  // items = simulated cycles
  state.counters["cycles"] = static_cast<double>(cycles);
  state.counters["words"] = static_cast<double>(s.words.size());
  state.counters["port_words"] = s.config.port_words;
  state.counters["tri_queue"] = s.config.tri_queue;
}

void BM_CycleEstimate(benchmark::State& state) {
  const BenchStream& s = stream();
  const CycleEstimate estimate(CycleConfig::of(s.config));
  uint64_t cycles = 0;
  for (auto _ : state) {
    const CycleEstimateRun r = estimate.run(s.words);
    cycles = r.cycles;
    benchmark::DoNotOptimize(r.scanlines.data());
  }
  report(state, cycles);
}
BENCHMARK(BM_CycleEstimate)->Unit(benchmark::kMicrosecond);

// What `shadesim cycles` runs by default: the figures and the breakdown.
void BM_CycleEstimateWithBreakdown(benchmark::State& state) {
  const BenchStream& s = stream();
  const CycleEstimate estimate(CycleConfig::of(s.config));
  uint64_t cycles = 0;
  for (auto _ : state) {
    const CycleEstimateRun r = estimate.run(s.words, true);
    cycles = r.cycles;
    benchmark::DoNotOptimize(r.breakdown->command_words);
  }
  report(state, cycles);
}
BENCHMARK(BM_CycleEstimateWithBreakdown)->Unit(benchmark::kMicrosecond);

// Clocks the cycle model over the stream once per iteration; returns its cycles.
uint64_t time_cycle_model(benchmark::State& state, const BenchStream& s) {
  const CycleConfig unit = CycleConfig::of(s.config);
  uint64_t cycles = 0;
  for (auto _ : state) {
    const CycleRun r = run_cycle_model(s.words, Stimulus{}, unit);
    cycles = r.cycles;
    benchmark::DoNotOptimize(r.scanlines.data());
  }
  return cycles;
}

void BM_CycleModel(benchmark::State& state) { report(state, time_cycle_model(state, stream())); }
BENCHMARK(BM_CycleModel)->Unit(benchmark::kMicrosecond);

// A scene rendered on its own configuration with `structure` applied, the stream saved once.
template <class Structure>
BenchStream structured_stream(const char* scene_path, Structure structure) {
  const std::string scene = std::string(SHADESIM_SOURCE_DIR) + "/" + scene_path;
  FrameOptions o;
  o.base = derive_config({scene}, DeriveOptions{}).config;
  structure(o.base);
  o.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene, o);
  return BenchStream{f.config, f.encoded.stream.encode()};
}

void run_structured(benchmark::State& state, const BenchStream& s) {
  const uint64_t cycles = time_cycle_model(state, s);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * cycles));
  state.counters["cycles"] = static_cast<double>(cycles);
}

void BM_CycleModelQueue(benchmark::State& state) {
  static const BenchStream s =
      structured_stream("bench/scenes/sphere_1024.json", [](UnitConfig& c) {
        c.port_words = 4;
        c.tri_queue = 4;
        c.span_setup = SpanSetupSite::kUnit;
      });
  run_structured(state, s);
}
BENCHMARK(BM_CycleModelQueue)->Name("CycleModelUnit/queue")->Unit(benchmark::kMicrosecond);

void BM_CycleModelLanes(benchmark::State& state) {
  static const BenchStream s =
      structured_stream("bench/scenes/sphere_1024.json", [](UnitConfig& c) { c.lanes = 4; });
  run_structured(state, s);
}
BENCHMARK(BM_CycleModelLanes)->Name("CycleModelUnit/lanes")->Unit(benchmark::kMicrosecond);

void BM_CycleModelMaterialBank(benchmark::State& state) {
  static const BenchStream s = structured_stream("scenes/hard/material_switch.json",
                                                 [](UnitConfig& c) { c.material_buffers = 2; });
  run_structured(state, s);
}
BENCHMARK(BM_CycleModelMaterialBank)
    ->Name("CycleModelUnit/material_bank")
    ->Unit(benchmark::kMicrosecond);

void BM_CycleModelHostSetup(benchmark::State& state) {
  static const BenchStream s =
      structured_stream("bench/scenes/sphere_1024.json", [](UnitConfig& c) {
        c.span_setup = SpanSetupSite::kHost;
        c.tri_queue = 1;
      });
  run_structured(state, s);
}
BENCHMARK(BM_CycleModelHostSetup)->Name("CycleModelUnit/host_setup")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace shadesim

BENCHMARK_MAIN();
