#include "derive/trial_unit.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "derive/budget.h"
#include "derive/colour_rules.h"
#include "derive/survey.h"
#include "derive/width_rules.h"
#include "host/encode.h"
#include "model/fixed_point.h"

namespace shadesim {
namespace {

// A trial unit for measuring: formats so wide that nothing wraps, saturates or is pre-shifted.
constexpr int kTrialSeriesIwl = 12, kTrialSeriesFrac = 40;
constexpr int kTrialCoefWl = 60, kTrialCoefIwl = 24, kTrialCoefWideIwl = 40;

void walk_stream(const CommandStream& stream, Walk& w) {
  const UnitConfig& c = stream.config;
  const double coef_lsb = std::ldexp(1.0, -c.coef.frac_bits());
  const int series_count = c.series_per_triangle();
  const TriangleCmd* tri = nullptr;
  for (const Command& cmd : stream.commands) {
    if (const auto* m = std::get_if<MaterialCmd>(&cmd)) {
      for (const int64_t a : m->ambient) {
        const double v = c.series.to_double(a);
        w.v_min = std::min(w.v_min, v);
        w.v_max = std::max(w.v_max, v);
      }
    } else if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
      tri = t;
      for (size_t i = 0; i < t->coef.size(); ++i) {
        const double a = std::fabs(static_cast<double>(t->coef[i])) * coef_lsb;
        w.coef_max = std::max(w.coef_max, a);
        double& term = w.term_max[i % kTermsPerSeries];
        term = std::max(term, a);
      }
    } else if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      if (!tri) throw std::logic_error("derive_config: span before any triangle");
      w.longest_span = std::max(w.longest_span, s->length);
      w.start_offset_min = std::min({w.start_offset_min, s->x0 - tri->xo, s->y - tri->yo});
      w.start_offset_max = std::max({w.start_offset_max, s->x0 - tri->xo, s->y - tri->yo});
      const Int128 dy = s->y - tri->yo;
      for (int x = s->x0; x < s->x0 + s->length; ++x) {
        const Int128 dx = x - tri->xo;
        const double adx = std::fabs(static_cast<double>(dx)),
                     ady = std::fabs(static_cast<double>(dy));
        w.max_offset = std::max(w.max_offset, static_cast<int>(std::max(adx, ady)));
        w.monomial_sum =
            std::max(w.monomial_sum, 1 + adx + ady + adx * adx + adx * ady + ady * ady);
        for (int i = 0; i < series_count; ++i) {
          const int64_t* k = &tri->coef[static_cast<size_t>(i) * kTermsPerSeries];
          // The exact quantized quadratic and its differences at this pixel (span setup's sums).
          const Int128 v = Int128{k[0]} + k[1] * dy + k[2] * dx + k[3] * dy * dy + k[4] * dx * dy +
                           k[5] * dx * dx;
          const Int128 d = Int128{k[2]} + k[4] * dy + k[5] * (2 * dx + 1);
          const double vd = static_cast<double>(v) * coef_lsb;
          w.v_min = std::min(w.v_min, vd);
          w.v_max = std::max(w.v_max, vd);
          w.diff_max = std::max({w.diff_max, std::fabs(static_cast<double>(d)) * coef_lsb,
                                 std::fabs(2.0 * static_cast<double>(k[5])) * coef_lsb});
        }
      }
    }
  }
}

// The scene prepared on a trial unit of cfg's structure that loses nothing. A sliver triangle
// (origin far outside it, huge gradient) can need more coefficient integer bits than the first
// trial holds: the second trades fraction bits the ranges do not need for integer bits.
// The walk takes the stream a chunk at a time as it is encoded, never the whole frame; `w`
// gains the scene's figures once a trial format holds every coefficient.
void walk_trial_frame(const FrameSet& frames, size_t scene, const UnitConfig& cfg, Walk& w) {
  UnitConfig trial = cfg;
  trial.series = FixedFormat{kTrialSeriesIwl + kTrialSeriesFrac, kTrialSeriesIwl, true,
                             cfg.series.quant, cfg.series.overflow};
  // The walk reads coefficients: unit span setup, every offset and term unpacked, whatever the
  // unit measured for has.
  trial.coef_term_iwl.clear();
  trial.span_setup = SpanSetupSite::kUnit;
  trial.tri_queue = 1;
  trial.offset_bits = UnitConfig::kMaxOffsetBits;
  std::string out_of_range;
  for (const int coef_iwl : {kTrialCoefIwl, kTrialCoefWideIwl}) {
    trial.coef =
        FixedFormat{kTrialCoefWl, coef_iwl, true, Quantization::kRoundNearest, Overflow::kSaturate};
    trial.validate();
    Walk scene_walk = w;
    const size_t over =
        frames.at(scene)
            .encode_chunks(trial, [&](CommandStream&& chunk) { walk_stream(chunk, scene_walk); })
            .coefficients_out_of_range;
    if (over == 0) {
      w = scene_walk;
      return;
    }
    out_of_range = std::to_string(over) + " Taylor coefficient(s) exceed the trial format " +
                   trial.coef.to_string();
  }
  throw std::invalid_argument(frames.path(scene) + ": " + out_of_range +
                              "; cannot measure their range");
}

}  // namespace

Walk measure_on_trial_unit(const FrameSet& frames, const UnitConfig& cfg) {
  Walk w;
  for (size_t i = 0; i < frames.size(); ++i) walk_trial_frame(frames, i, cfg, w);
  return w;
}

void record_walk(const Walk& w, ConfigMeasurements& ms) {
  ms.longest_span = w.longest_span;
  ms.max_offset = w.max_offset;
  ms.start_offset_min = w.start_offset_min;
  ms.start_offset_max = w.start_offset_max;
  ms.max_monomial_sum = w.monomial_sum;
  ms.series_min = w.v_min;
  ms.series_max = w.v_max;
  ms.difference_max = w.diff_max;
  ms.coef_max = w.coef_max;
}

ConfigMeasurements measure_scene_on(const PreparedScene& frame, const UnitConfig& unit) {
  const FrameSet frames(frame);
  const std::vector<SceneInfo> scenes = load_scenes(frames);
  DeriveOptions options;
  options.budget_lsb = frame.key().budget_lsb;
  options.max_depth = frame.key().max_depth;
  const Budget budget = choose_budget(scenes, options);
  ConfigMeasurements ms;
  set_budget(budget.lsb, ms);
  ms.max_width = scenes.front().scene.width;
  ms.max_height = scenes.front().scene.height;
  record_walk(measure_on_trial_unit(frames, unit), ms);
  ms.gain = series_gain(scenes, unit).total;
  ms.colour_max = light_colours(scenes, unit).max();
  ms.product_max = colour_product_max(ms.colour_max, ms.series_max);
  return ms;
}

}  // namespace shadesim
