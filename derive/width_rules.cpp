#include "derive/width_rules.h"

#include <algorithm>
#include <cmath>

#include "derive/colour_rules.h"
#include "derive/helpers.h"
#include "host/frame.h"
#include "host/specular_setup.h"
#include "model/command_stream.h"

namespace shadesim {
namespace {

// Fewest integer bits (sign included) of a signed format holding every value in [lo, hi].
int signed_integer_bits(double lo, double hi) {
  int iwl = 1;
  while (iwl < 62 && (lo < -std::ldexp(1.0, iwl - 1) || hi >= std::ldexp(1.0, iwl - 1))) ++iwl;
  return iwl;
}

// The largest slope of the specular unit's output with respect to one of its series values,
// summed over the series it reads: t^n has slope <= n on [0, 1], and the series carries an
// affine image of t (scale from plan_specular, which includes any pre-shift).
double unit_slope(const UnitConfig& config, double n) {
  if (config.specular.kind == SpecularUnitKind::kNone) return 0;  // no series, no term
  const SpecularSeriesPlan plan = plan_specular(config, n);
  const double scale = std::fabs(plan.affine.front().first);
  switch (config.specular.kind) {
    case SpecularUnitKind::kIdeal:
      return n / scale;
    case SpecularUnitKind::kLut:
      // per-exponent: table of t^n; shared: exp(-k (1 - t)) has slope <= k.
      return (config.specular.lut.addressing == LutAddressing::kShared ? plan.parameter : n) /
             scale;
    case SpecularUnitKind::kWpow:
      // (zeta (t - 1) + 1)^m with the base clamped to [0, 1]: slope <= m zeta in t.
      return plan.effective_m * plan.parameter / scale;
    case SpecularUnitKind::kSchlick: {
      // S = num / den with num = t / n', den = (n' - (n' - 1) t) / n' on t in [0, 1]:
      // |dS/dnum| = 1/den <= n' and |dS/dden| = num/den^2 <= n'.
      const double np = std::max(1.0, plan.parameter);
      return 2.0 * np;
    }
    case SpecularUnitKind::kNone:
      return 0;
  }
  return n;
}

// Saturating series must also hold the differences span setup adds to them; wrapping ones are
// exact modulo 2^iwl whatever the differences reach.
int series_integer_bits(const Walk& w, const UnitConfig& cfg) {
  const bool wraps = cfg.series.overflow == Overflow::kWrap;
  const double need_lo = wraps ? w.v_min : std::min(w.v_min, -w.diff_max);
  const double need_hi = wraps ? w.v_max : std::max(w.v_max, w.diff_max);
  return std::max(2, signed_integer_bits(need_lo, need_hi));
}

// The largest factor by which light l's diffuse series reaches an output channel: 1 with its
// colour rolled in; when multiplied, the largest kd_c L_c it is multiplied by.
double diffuse_gain(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg, size_t l) {
  if (!cfg.diffuse_multiply()) return 1.0;
  double gain = 0;
  for (const auto& s : scenes) {
    if (l >= s.scene.lights.size()) continue;
    for (const auto& m : s.scene.materials) {
      for (int c = 0; c < 3; ++c) {
        gain = std::max(gain, channel(m.diffuse, c) * channel(s.scene.lights[l].colour, c));
      }
    }
  }
  return gain;
}

// The same for light l's specular series: through the unit, so its slope times the colour.
double specular_gain(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg, size_t l) {
  double gain = 0;
  for (const auto& s : scenes) {
    if (l >= s.scene.lights.size()) continue;
    for (const auto& m : s.scene.materials) {
      double colour = 0;
      for (int c = 0; c < 3; ++c) {
        colour = std::max(colour, channel(m.specular, c) * channel(s.scene.lights[l].colour, c));
      }
      if (colour > 0) gain = std::max(gain, colour * unit_slope(cfg, m.exponent));
    }
  }
  return gain;
}

struct Bits {
  int bits = 0;
  std::string why;
};

Bits coef_integer_bits(const Walk& w, const UnitConfig& cfg) {
  if (cfg.coef.overflow == Overflow::kWrap) {
    return {cfg.series.iwl,
            "coefficients reach |T| = " + fmt(w.coef_max) + " (" +
                std::to_string(signed_integer_bits(-w.coef_max, w.coef_max)) +
                " integer bits unwrapped); the format wraps, exact modulo 2^iwl because span "
                "setup multiplies "
                "coefficients only by integers, so the series' " +
                std::to_string(cfg.series.iwl) +
                " integer bits suffice (UnitConfig needs coef.iwl >= series.iwl when wrapping)"};
  }
  const int iwl = signed_integer_bits(-w.coef_max, w.coef_max);
  return {iwl, "coefficients reach |T| = " + fmt(w.coef_max) + ", which " + std::to_string(iwl) +
                   " saturating integer bits hold"};
}

// A coefficient's rounding error reaches a pixel times its monomial and then the gain, so the
// largest monomial sum of any pixel bounds it.
int coef_fraction_bits(const Walk& w, const ConfigMeasurements& ms, const UnitConfig& cfg) {
  const double allowed = ms.coef_share_lsb * std::ldexp(1.0, -cfg.out_bits);
  const bool rounds = cfg.coef.quant == Quantization::kRoundNearest;
  int frac = 0;
  while (frac < 60 && ms.gain * std::ldexp(rounds ? 0.5 : 1.0, -frac) * w.monomial_sum > allowed) {
    ++frac;
  }
  return frac;
}

}  // namespace

const DerivationRule kGainRule = {
    "G",
    "the gain of the series into one output channel: the sum over lights of (1, or with the "
    "diffuse colour multiplied the largest kd_c L_c, + the largest specular colour x the "
    "specular unit's slope with respect to its series): a diffuse series enters the output with "
    "its colour rolled in, a specular one through the unit (t^n has slope <= n on [0, 1]; a "
    "LUT's, W_m's or Schlick's own slope) through setup's pre-scaling"};

// Gain of the series into one output channel: every light's errors add up in it.
Gain series_gain(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg) {
  Gain g;
  for (int l = 0; l < cfg.lights; ++l) {
    const double diffuse = diffuse_gain(scenes, cfg, static_cast<size_t>(l));
    const double spec = specular_gain(scenes, cfg, static_cast<size_t>(l));
    g.total += diffuse + spec;
    g.detail +=
        (g.detail.empty() ? "" : " + ") + std::string("(") + fmt(diffuse) + " + " + fmt(spec) + ")";
  }
  return g;
}

const DerivationRule kXyBitsRule = {
    "xy_bits", "enough unsigned bits for the largest image width and height (at least 4)"};

// Every coordinate 0..size-1 in unsigned bits: prepare_frame needs size <= 2^xy_bits.
std::string derive_xy_bits(const std::vector<SceneInfo>& scenes, UnitConfig& cfg,
                           ConfigMeasurements& ms) {
  for (const auto& s : scenes) {
    ms.max_width = std::max(ms.max_width, s.scene.width);
    ms.max_height = std::max(ms.max_height, s.scene.height);
  }
  const int size = std::max(ms.max_width, ms.max_height);
  const int xy = xy_bits_for_image(ms.max_width, ms.max_height);
  cfg.xy_bits = std::max(4, xy);
  return "largest image " + std::to_string(ms.max_width) + "x" + std::to_string(ms.max_height) +
         ": " + std::to_string(size) + " <= 2^" + std::to_string(cfg.xy_bits) +
         (xy < 4 ? " (at least 4)" : "");
}

const DerivationRule kOffsetBitsRule = {
    "offset_bits",
    "enough signed bits for the largest |dx|, |dy| of a span's first pixel from its triangle's "
    "origin, so no triangle is re-origined"};

// Span setup's offsets: the fewest signed bits that hold every span start's dx, dy, so the
// encoder moves no origin of these scenes: -2^(b-1) <= min and max <= 2^(b-1) - 1.
std::string derive_offset_bits(const Walk& w, UnitConfig& cfg) {
  int bits = 2;
  while (-(1 << (bits - 1)) > w.start_offset_min || (1 << (bits - 1)) - 1 < w.start_offset_max) {
    ++bits;
  }
  cfg.offset_bits = bits;
  return "spans start at dx, dy in " + std::to_string(w.start_offset_min) + ".." +
         std::to_string(w.start_offset_max) + " px from their triangle's origin, within " +
         std::to_string(-(1 << (bits - 1))) + ".." + std::to_string((1 << (bits - 1)) - 1) +
         ": no origin moved, no triangle re-origined";
}

const DerivationRule kSeriesRule = {
    "series",
    "integer bits: the fewest (>= 2) holding every series value at every pixel and every ambient "
    "word (measured on a trial unit wide enough that nothing wraps and setup pre-shifts nothing) "
    "and every colour product (intensity or N.L times a colour word) PixelCombine brings into "
    "the series format; saturating (:sat), also every difference d and d2. Fraction bits F: the "
    "drift bound of the forward differences over the longest span L, 2^-F (1 + L(L-1)/2) with "
    "truncation (half with rounding), times G, <= budget/4 LSB; at least out_bits"};

std::string derive_series(const std::vector<SceneInfo>& scenes, const Walk& w,
                          ConfigMeasurements& ms, UnitConfig& cfg) {
  // PixelCombine brings each colour product (intensity or N.L, <= 1, times a colour word) into
  // the series format by the series rule before the exact sum: the series holds them too.
  ms.colour_max = light_colours(scenes, cfg).max();
  ms.product_max = colour_product_max(ms.colour_max, w.v_max);
  const int value_iwl = series_integer_bits(w, cfg);
  const int iwl = std::max(value_iwl, signed_integer_bits(0.0, ms.product_max));
  cfg.series.iwl = iwl;
  // The gain's specular plan reads only iwl; the fraction bits it asks for come after it.
  cfg.series.wl = iwl + cfg.out_bits;
  const Gain gain = series_gain(scenes, cfg);
  ms.gain = gain.total;
  const bool rounds = cfg.series.quant == Quantization::kRoundNearest;
  const int frac = std::max(
      cfg.out_bits,
      drift_fraction_bits(ms.longest_span, gain.total, ms.drift_share_lsb, cfg.out_bits, rounds));
  cfg.series.wl = iwl + frac;
  const bool wraps = cfg.series.overflow == Overflow::kWrap;
  const double steps = 1.0 + ms.longest_span * (ms.longest_span - 1.0) / 2.0;
  return "integer " + std::to_string(iwl) + ": series values at the pixels span [" + fmt(w.v_min) +
         ", " + fmt(w.v_max) + "]" + (wraps ? "" : " and differences reach " + fmt(w.diff_max)) +
         (iwl > value_iwl ? ", colour products reach " + fmt(ms.product_max) : std::string()) +
         "; fraction " + std::to_string(frac) +
         ": longest span L = " + std::to_string(ms.longest_span) +
         ", drift bound 2^-F (1 + L(L-1)/2) = 2^-F x " + fmt(steps, 8) +
         (rounds ? " / 2 (rounding)" : "") + " x gain " + fmt(gain.total) + " = " + gain.detail +
         (cfg.diffuse_multiply() ? " (per light: max kd L + spec colour x unit slope) <= "
                                 : " (per light: 1 + spec colour x unit slope) <= ") +
         fmt(ms.drift_share_lsb) + " LSB (budget/4)" +
         (frac == cfg.out_bits ? " (at least out_bits)" : "");
}

const DerivationRule kCoefRule = {
    "coef",
    "integer bits: wrapping, the series' (span setup multiplies coefficients only by integers, "
    "so the sums are exact modulo 2^iwl, and UnitConfig needs coef.iwl >= series.iwl); "
    "saturating, the measured coefficient range. Fraction bits F: coefficient rounding 2^-(F+1) "
    "(2^-F truncating) times the largest 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 of a pixel from its "
    "triangle's origin, times G, <= budget/4 LSB"};

std::string derive_coef(const Walk& w, const ConfigMeasurements& ms, UnitConfig& cfg) {
  const Bits integer = coef_integer_bits(w, cfg);
  const int frac = coef_fraction_bits(w, ms, cfg);
  cfg.coef.iwl = integer.bits;
  cfg.coef.wl = integer.bits + frac;
  const bool rounds = cfg.coef.quant == Quantization::kRoundNearest;
  return "integer: " + integer.why + "; fraction " + std::to_string(frac) + ": pixels lie up to " +
         std::to_string(ms.max_offset) +
         " px from their triangle's origin, max 1+|dx|+|dy|+dx^2+|dx dy|+dy^2 = " +
         fmt(w.monomial_sum, 6) + ", so coefficient rounding " + (rounds ? "2^-(F+1)" : "2^-F") +
         " x " + fmt(w.monomial_sum, 6) + " x gain " + fmt(ms.gain) +
         " <= " + fmt(ms.coef_share_lsb) + " LSB (budget/4)";
}

const DerivationRule kCoefTermsRule = {
    "coef_term_iwl",
    "coefficient packing: T0 keeps coef's integer bits (it wraps); T1..T5 the fewest saturating "
    "integer bits holding every measured |T_t| + 1 LSB"};

// Coefficient packing: T0 keeps coef's integer bits (it wraps); T1..T5 get the fewest
// saturating integer bits that hold every measured |T_t| plus one final LSB (the trial's
// finer coefficients may round up into it).
std::string derive_term_widths(const Walk& w, UnitConfig& cfg) {
  const int coef_iwl = cfg.coef.iwl, coef_frac = cfg.coef.frac_bits();
  cfg.coef_term_iwl.assign(kTermsPerSeries, coef_iwl);
  std::string why = "T0 keeps coef's " + std::to_string(coef_iwl) + " integer bits (it wraps)";
  const double final_lsb = std::ldexp(1.0, -coef_frac);
  for (int t = 1; t < kTermsPerSeries; ++t) {
    const double reach = w.term_max[static_cast<size_t>(t)] + final_lsb;
    const int iwl = std::clamp(signed_integer_bits(-reach, reach), 2 - coef_frac, coef_iwl);
    cfg.coef_term_iwl[static_cast<size_t>(t)] = iwl;
    why += "; T" + std::to_string(t) + " reaches |T| = " + fmt(w.term_max[static_cast<size_t>(t)]) +
           ": " + std::to_string(iwl) + " integer bits (saturating)";
  }
  return why;
}

int drift_fraction_bits(int longest_span, double gain, double share_lsb, int out_bits,
                        bool rounding) {
  const double L = std::max(1, longest_span);
  const double steps = 1.0 + L * (L - 1.0) / 2.0;
  const double allowed = share_lsb * std::ldexp(1.0, -out_bits);
  for (int f = 0; f <= 60; ++f) {
    const double drift = std::ldexp(steps, -f) * (rounding ? 0.5 : 1.0);
    if (gain * drift <= allowed) return f;
  }
  return 61;
}

}  // namespace shadesim
