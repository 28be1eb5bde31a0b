// Model throughput on a 1024x1024 scene, triangle setup excluded (the stream is prepared once).
//   ForwardDifference: span setup + v += d; d += d2 for every series of every pixel - the
//                      datapath Bishop & Weimer reduce shading to (target >= 50 M pixels/s).
//   ShadeUnit:         the whole bit-accurate unit per pixel (series, specular unit, combine).
#include <benchmark/benchmark.h>

#include <iostream>

#include "host/frame.h"
#include "model/series_engine.h"
#include "model/shade_unit.h"
#include "model/span_setup.h"

namespace shadesim {
namespace {

const PreparedFrame& frame() {
  static const PreparedFrame f = [] {
    FrameOptions o;
    return prepare_frame(SHADESIM_SOURCE_DIR "/bench/scenes/sphere_1024.json", o);
  }();
  return f;
}

void BM_ForwardDifference(benchmark::State& state) {
  const PreparedFrame& f = frame();
  const UnitConfig& cfg = f.config;
  const SpanSetup setup(cfg.coef, cfg.series, cfg.offset_bits);
  const int n = cfg.series_per_triangle();
  SeriesBank bank(cfg.series, n);
  int64_t checksum = 0;
  size_t pixels = 0;
  for (auto _ : state) {
    const TriangleCmd* tri = nullptr;
    for (const auto& cmd : f.encoded.stream.commands) {
      if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
        tri = t;
      } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
        for (int i = 0; i < n; ++i) {
          bank.load(i, setup(&tri->coef[static_cast<size_t>(i) * kTermsPerSeries], s->x0 - tri->xo,
                             s->y - tri->yo));
        }
        for (int32_t k = 0; k < s->length; ++k) {
          checksum += bank.values()[0];
          bank.step();
        }
        pixels += static_cast<size_t>(s->length);
      }
    }
  }
  benchmark::DoNotOptimize(checksum);
  state.SetItemsProcessed(static_cast<int64_t>(pixels));
  state.counters["series"] = n;
  state.counters["pixels_per_frame"] = static_cast<double>(f.encoded.stats.pixels);
}
BENCHMARK(BM_ForwardDifference)->Unit(benchmark::kMillisecond);

void BM_ShadeUnit(benchmark::State& state) {
  const PreparedFrame& f = frame();
  ShadeUnit unit(f.config);
  uint64_t checksum = 0;
  size_t pixels = 0;
  for (auto _ : state) {
    for (const auto& cmd : f.encoded.stream.commands) {
      unit.consume(cmd, [&](const PixelOut& p) {
        checksum += p.colour[0];
        ++pixels;
      });
    }
  }
  benchmark::DoNotOptimize(checksum);
  state.SetItemsProcessed(static_cast<int64_t>(pixels));
  state.SetLabel("specular=" + to_string(f.config.specular.kind));
}
BENCHMARK(BM_ShadeUnit)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace shadesim

BENCHMARK_MAIN();
