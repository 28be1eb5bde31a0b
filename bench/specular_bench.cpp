// Model throughput of each specular unit: evaluations per second on one core, through the
// SpecularUnit slot as the shading unit calls it, over a sweep of t values.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "host/specular_setup.h"
#include "model/specular_unit.h"

namespace shadesim {
namespace {

void run_unit(benchmark::State& state, SpecularConfig spec) {
  UnitConfig cfg;
  cfg.specular = spec;
  const double n = 64.0;
  const SpecularSeriesPlan plan = plan_specular(cfg, n);
  SpecularUnit unit(cfg);
  MaterialCmd m;
  m.exponent = static_cast<int64_t>(std::ldexp(n, kExponentFracBits));
  m.unit_params = plan.unit_params;
  unit.load_material(m);
  for (const TableCmd& t : shared_lut_tables(cfg)) unit.load_table(t);
  for (const TableCmd& t : plan.tables) unit.load_table(t);
  // Series values for 4096 t in [-0.1, 1.1], as the series engines would present them.
  const int per = cfg.specular.series_per_light();
  std::vector<int64_t> series;
  for (int i = 0; i < 4096; ++i) {
    const double t = -0.1 + 1.2 * i / 4095.0;
    for (int k = 0; k < per; ++k)
      series.push_back(cfg.series.from_double(plan.affine[k].first * t + plan.affine[k].second));
  }
  int64_t sum = 0;
  for (auto _ : state) {
    for (size_t i = 0; i < series.size(); i += static_cast<size_t>(per))
      sum += unit.evaluate(&series[i]);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 4096);
}

SpecularConfig with(SpecularUnitKind k) {
  SpecularConfig s;
  s.kind = k;
  return s;
}

void BM_Ideal(benchmark::State& s) { run_unit(s, with(SpecularUnitKind::kIdeal)); }
void BM_LutPerExponentA10(benchmark::State& s) { run_unit(s, with(SpecularUnitKind::kLut)); }
void BM_LutInterpA8F8(benchmark::State& s) {
  SpecularConfig c = with(SpecularUnitKind::kLut);
  c.lut.addr_bits = 8;
  c.lut.entry_bits = 16;
  c.lut.interp_bits = 8;
  run_unit(s, c);
}
void BM_LutSharedExpA12(benchmark::State& s) {
  SpecularConfig c = with(SpecularUnitKind::kLut);
  c.lut.addressing = LutAddressing::kShared;
  c.lut.index = LutIndex::kNearest;
  c.lut.addr_bits = 12;
  c.lut.entry_bits = 16;
  run_unit(s, c);
}
void BM_SchlickQ16(benchmark::State& s) { run_unit(s, with(SpecularUnitKind::kSchlick)); }
void BM_WpowM16B16(benchmark::State& s) { run_unit(s, with(SpecularUnitKind::kWpow)); }

BENCHMARK(BM_Ideal);
BENCHMARK(BM_LutPerExponentA10);
BENCHMARK(BM_LutInterpA8F8);
BENCHMARK(BM_LutSharedExpA12);
BENCHMARK(BM_SchlickQ16);
BENCHMARK(BM_WpowM16B16);

}  // namespace
}  // namespace shadesim

BENCHMARK_MAIN();
