#include "derive/derive_config.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "host/frame.h"
#include "host/gate_flips.h"
#include "host/parallel.h"
#include "host/scene_error.h"
#include "derive/specular_candidates.h"
#include "host/specular_setup.h"
#include "derive/throughput_choice.h"
#include "model/coef_packing.h"
#include "model/command_stream.h"
#include "model/cycle_estimate.h"
#include "model/wpow_unit.h"

namespace shadesim {
namespace {

// Shares of the budget (output LSBs) the fixed-point error may add to the Taylor error.
constexpr double kDriftShare = 0.25;
constexpr double kCoefShare = 0.25;
// Shares for the colour words' rounding and the specular unit's output truncation (3/16 and
// 1/16), so the fixed-point error adds at most 3/4 of the budget to the Taylor error.
constexpr double kColourShare = 0.1875;
constexpr double kSpecularOutShare = 0.0625;
// Neither is narrowed below the default's fraction bits: the shares bound the worst case, and
// narrower colours or outputs were measured to cost suzanne's own unit its 1 LSB (2 LSB).
int min_colour_frac() { return UnitConfig{}.spec_colour.frac_bits(); }
int min_specular_out_frac() { return SpecularConfig{}.out.frac_bits(); }

// A trial unit for measuring: formats so wide that nothing wraps, saturates or is pre-shifted.
constexpr int kTrialSeriesIwl = 12, kTrialSeriesFrac = 40;
constexpr int kTrialCoefWl = 60, kTrialCoefIwl = 24, kTrialCoefWideIwl = 40;

double channel(const Vec3& v, int c) { return c == 0 ? v.x : (c == 1 ? v.y : v.z); }

std::string fmt(double x, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << x;
  return os.str();
}

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

struct SceneInfo {
  std::string path;
  const Scene& scene;  // the prepared frame's (FrameSet)
};

// Numbers measured on one scene's trial frame, merged over scenes.
struct Walk {
  int longest_span = 0, max_offset = 0;
  int start_offset_min = 0, start_offset_max = 0;  // of dx, dy at a span's first pixel
  double monomial_sum = 0, v_min = 0, v_max = 0, diff_max = 0, coef_max = 0;
  std::array<double, kTermsPerSeries> term_max{};  // largest |T_t| of any series
};

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

// derive_widths' steps, in the order it runs them: each reads only what the steps before it set.

std::vector<SceneInfo> load_scenes(const FrameSet& frames) {
  if (frames.size() == 0) throw std::invalid_argument("derive_config: no scenes given");
  std::vector<SceneInfo> scenes;
  for (size_t i = 0; i < frames.size(); ++i)
    scenes.push_back({frames.path(i), frames.at(i).scene()});
  return scenes;
}

struct Budget {
  double lsb = 0;
  std::string from;  // "--budget" or the scene it is taken from
};

void check_budget(double lsb) {
  if (!(lsb > 0) || !std::isfinite(lsb)) {
    throw std::invalid_argument("derive_config: budget must be a positive number of LSBs, got " +
                                fmt(lsb));
  }
}

// The strictest scene's budget unless one is given: one unit must meet every scene's.
Budget choose_budget(const std::vector<SceneInfo>& scenes, const DeriveOptions& options) {
  Budget budget;
  if (options.budget_lsb) {
    budget = {*options.budget_lsb, "--budget"};
  } else {
    budget = {scenes.front().scene.error_budget_lsb, scenes.front().path};
    for (const auto& s : scenes) {
      if (s.scene.error_budget_lsb < budget.lsb) budget = {s.scene.error_budget_lsb, s.path};
    }
  }
  check_budget(budget.lsb);
  return budget;
}

// The budget and each fixed-point error's share of it.
void set_budget(double lsb, ConfigMeasurements& ms) {
  ms.budget_lsb = lsb;
  ms.drift_share_lsb = kDriftShare * lsb;
  ms.coef_share_lsb = kCoefShare * lsb;
  ms.colour_share_lsb = kColourShare * lsb;
  ms.specular_out_share_lsb = kSpecularOutShare * lsb;
}

// Why each derived field has its value, kept until the unit is final (field_reasons lists them).
struct FieldWhys {
  std::string channels, lights, diffuse_colour, specular, xy_bits, offset_bits, series, coef,
      coef_term_iwl, span_setup, spec_colour, specular_out;
};

// What the colour words carry, per light: the largest specular colour ks_c L_c and, with the
// diffuse colour multiplied, the largest kd_c L_c, over every scene, material and channel.
struct LightColours {
  std::vector<double> specular, diffuse;  // indexed by light
  double max() const {
    double m = 0;
    for (double v : specular) m = std::max(m, v);
    for (double v : diffuse) m = std::max(m, v);
    return m;
  }
};

LightColours light_colours(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg) {
  LightColours out;
  out.specular.assign(static_cast<size_t>(cfg.lights), 0.0);
  out.diffuse.assign(static_cast<size_t>(cfg.lights), 0.0);
  for (const auto& s : scenes) {
    for (size_t l = 0; l < s.scene.lights.size() && l < out.specular.size(); ++l) {
      const Vec3& light = s.scene.lights[l].colour;
      for (const auto& m : s.scene.materials) {
        for (int c = 0; c < 3; ++c) {
          out.specular[l] = std::max(out.specular[l], channel(m.specular, c) * channel(light, c));
          if (cfg.diffuse_multiply())
            out.diffuse[l] = std::max(out.diffuse[l], channel(m.diffuse, c) * channel(light, c));
        }
      }
    }
  }
  return out;
}

// The largest colour product PixelCombine brings into the series format: a colour word times
// the specular intensity (<= 1) or, multiplied, times N.L, whose series overshoots 1 where the
// Taylor expansion does (the largest series value measured).
double colour_product_max(double colour_max, double series_max) {
  return colour_max * std::max(1.0, series_max);
}

// Fewest integer bits (>= 1: UnitConfig holds 1.0) of an unsigned format with `frac` fraction
// bits whose largest value, 2^iwl - 2^-frac, is at least `max`, so rounding never saturates.
int unsigned_integer_bits(double max, int frac) {
  int iwl = 1;
  while (iwl < 40 && std::ldexp(1.0, iwl) - std::ldexp(1.0, -frac) < max) ++iwl;
  return iwl;
}

// The smallest fraction bits F with 2^-F x weight <= allowed (weight 0: none needed).
int fraction_bits_for(double weight, double allowed) {
  int frac = 0;
  while (frac < 40 && std::ldexp(weight, -frac) > allowed) ++frac;
  return frac;
}

// spec_colour carries ks_c L_c (and with the multiply kd_c L_c) per light and channel. Integer
// bits: the largest colour, unsaturated. Fraction bits F: in one channel each light's words
// reach the output as rounding 2^-(F+1) times the specular intensity (<= 1) and, multiplied,
// 2^-(F+1) times N.L (<= 1) plus N.L truncated to F bits (2^-F) times kd_c L_c; summed over the
// lights within 3/16 of the budget; at least the default's fraction bits.
std::string derive_spec_colour(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                               UnitConfig& cfg) {
  const bool specular = cfg.specular.kind != SpecularUnitKind::kNone;
  if (!specular && !cfg.diffuse_multiply()) {
    return "not read: no specular term and the diffuse colour is rolled into the series "
           "(default kept)";
  }
  const LightColours colours = light_colours(scenes, cfg);
  double weight = 0;
  for (int l = 0; l < cfg.lights; ++l) {
    const size_t i = static_cast<size_t>(l);
    if (colours.specular[i] > 0) weight += 0.5;
    if (cfg.diffuse_multiply() && colours.diffuse[i] > 0) weight += 0.5 + colours.diffuse[i];
  }
  const double allowed = ms.colour_share_lsb * std::ldexp(1.0, -cfg.out_bits);
  const int rule = fraction_bits_for(weight, allowed);
  const int frac = std::max(min_colour_frac(), rule);
  const double top = colours.max();
  const int iwl = unsigned_integer_bits(top, frac);
  cfg.spec_colour.iwl = iwl;
  cfg.spec_colour.wl = iwl + frac;
  return "integer " + std::to_string(iwl) + ": colours (ks_c L_c" +
         (cfg.diffuse_multiply() ? std::string(", kd_c L_c") : std::string()) + ") reach " +
         fmt(top) + " < 2^" + std::to_string(iwl) + " (unsaturated); fraction " +
         std::to_string(frac) + ": rounding 2^-(F+1) per word" +
         (cfg.diffuse_multiply() ? " and N.L truncated to F bits times kd_c L_c" : "") +
         ", summed over the lights (" + fmt(weight) + " x 2^-F), <= " + fmt(ms.colour_share_lsb) +
         " LSB (3/16 of the budget)" +
         (frac > rule ? " (at least the default's " + std::to_string(min_colour_frac()) + ")" : "");
}

// The specular unit's output s (in [0, 1]) is truncated to F fraction bits, and each light's
// s x ks_c L_c adds to a channel: 2^-F x the sum over lights of the largest ks_c L_c, within
// budget/16; at least the default's fraction bits.
std::string derive_specular_out(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                                UnitConfig& cfg) {
  if (cfg.specular.kind == SpecularUnitKind::kNone) return "";
  const LightColours colours = light_colours(scenes, cfg);
  double weight = 0;
  for (double k : colours.specular) weight += k;
  const double allowed = ms.specular_out_share_lsb * std::ldexp(1.0, -cfg.out_bits);
  const int rule = fraction_bits_for(weight, allowed);
  const int frac = std::max(min_specular_out_frac(), rule);
  cfg.specular.out.iwl = 1;
  cfg.specular.out.wl = 1 + frac;
  return "; out u1." + std::to_string(frac) +
         ": the output truncated to F bits times the "
         "specular colours summed over the lights (" +
         fmt(weight) + " x 2^-F) <= " + fmt(ms.specular_out_share_lsb) + " LSB (budget/16)" +
         (frac > rule ? " (at least the default's " + std::to_string(min_specular_out_frac()) + ")"
                      : "");
}

std::string derive_channels(const std::vector<SceneInfo>& scenes, UnitConfig& cfg) {
  for (const auto& s : scenes) {
    if (!s.scene.is_grey()) {
      cfg.channels = 3;
      return s.path + " has colour: three channels";
    }
  }
  cfg.channels = 1;
  return "every scene is grey: one channel carries the image";
}

std::string derive_lights(const std::vector<SceneInfo>& scenes, UnitConfig& cfg) {
  int lights = 0;
  std::string lights_scene;
  for (const auto& s : scenes) {
    if (static_cast<int>(s.scene.lights.size()) > lights) {
      lights = static_cast<int>(s.scene.lights.size());
      lights_scene = s.path;
    }
  }
  cfg.lights = lights;
  return "the most directional lights of any scene (" + lights_scene + ")";
}

// One N.L series per light in place of one per light and channel, where that removes series.
std::string derive_diffuse_colour(const DeriveOptions& options, UnitConfig& cfg) {
  cfg.diffuse_colour = options.diffuse_colour.value_or(cfg.channels > 1 ? DiffuseColour::kMultiply
                                                                        : DiffuseColour::kSeries);
  if (options.diffuse_colour) return "as requested (--diffuse-colour)";
  if (cfg.channels > 1) {
    return "multiply: one N.L series per light (" + std::to_string(cfg.lights) +
           ") in place of one per light and channel (" + std::to_string(cfg.lights * cfg.channels) +
           "); each pixel multiplies max(0, N.L) by kd_c L_c from the MATERIAL";
  }
  return "series: one channel, so a multiply would remove no series";
}

// A specular term: a non-zero specular colour under a light of non-zero colour in some channel.
// Without one in any scene the unit needs no specular unit.
bool has_specular_term(const std::vector<SceneInfo>& scenes) {
  for (const auto& s : scenes) {
    for (const auto& m : s.scene.materials) {
      for (const auto& light : s.scene.lights) {
        for (int c = 0; c < 3; ++c) {
          if (channel(m.specular, c) * channel(light.colour, c) != 0) return true;
        }
      }
    }
  }
  return false;
}

// The specular unit the materials name. One unit serves every scene, so where it matters (some
// scene has a specular term) every material must name the same one.
SpecularUnitKind named_unit(const std::vector<SceneInfo>& scenes, bool specular) {
  const SceneInfo& unit_scene = scenes.front();
  const Material& unit_material = unit_scene.scene.materials.front();
  if (!specular) return unit_material.unit;
  for (const auto& s : scenes) {
    for (const auto& m : s.scene.materials) {
      if (m.unit != unit_material.unit) {
        throw std::invalid_argument(
            "derive_config: one unit serves every scene, but " + unit_scene.path + " (material '" +
            unit_material.name + "') names the specular unit " + to_string(unit_material.unit) +
            " and " + s.path + " (material '" + m.name + "') names " + to_string(m.unit) +
            "; derive them separately or make the materials agree");
      }
    }
  }
  return unit_material.unit;
}

struct SpecularChoice {
  bool substitute = false;  // DerivedConfig::substitute
  std::string why;
};

SpecularChoice choose_specular_unit(const std::vector<SceneInfo>& scenes,
                                    const DeriveOptions& options, UnitConfig& cfg) {
  const bool specular = has_specular_term(scenes);
  const SpecularUnitKind named = named_unit(scenes, specular);
  SpecularChoice choice;
  if (!specular) {
    cfg.specular.kind = SpecularUnitKind::kNone;
    choice.why =
        std::string(scenes.size() == 1 ? "the scene has no" : "no scene has a") +
        " specular term (every material's specular colour times every light's colour "
        "is 0): no specular unit and no specular series" +
        (named == SpecularUnitKind::kNone ? ""
                                          : " (the materials name " + to_string(named) +
                                                ", which adds 0 without a specular colour)");
  } else if (named == SpecularUnitKind::kIdeal) {
    cfg.specular = options.ideal_substitute;
    choice.substitute = cfg.specular.kind != SpecularUnitKind::kIdeal;
    choice.why = cfg.specular.kind == SpecularUnitKind::kIdeal
                     ? "the scenes name ideal, kept as asked: exact pow, not hardware (its RTL "
                       "slot outputs 0)"
                     : "the scenes name ideal, which is not hardware (its RTL slot outputs 0); "
                       "substituted by " +
                           cfg.specular.describe();
  } else {
    cfg.specular.kind = named;
    choice.why = "the unit the scenes' materials name, default widths";
  }
  if (options.specular_trial) {
    cfg.specular = *options.specular_trial;
    if (named != SpecularUnitKind::kIdeal)
      choice.why = "the unit the scenes' materials name, with the fields searched below";
  }
  cfg.specular.validate();
  return choice;
}

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

// The scenes' values measured on a trial unit of cfg's structure whose formats lose nothing, so
// the widths fit the values themselves rather than what a narrower unit wraps or saturates.
// The scene prepared on a trial unit of cfg's structure that loses nothing. A sliver triangle
// (origin far outside it, huge gradient) can need more coefficient integer bits than the first
// trial holds: the second trades fraction bits the ranges do not need for integer bits.
EncodedFrame trial_frame(const FrameSet& frames, size_t scene, const UnitConfig& cfg) {
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
    EncodedFrame frame = frames.at(scene).encode(trial);
    const size_t over = frame.stats.coefficients_out_of_range;
    if (over == 0) return frame;
    out_of_range = std::to_string(over) + " Taylor coefficient(s) exceed the trial format " +
                   trial.coef.to_string();
  }
  throw std::invalid_argument(frames.path(scene) + ": " + out_of_range +
                              "; cannot measure their range");
}

Walk measure_on_trial_unit(const FrameSet& frames, const UnitConfig& cfg) {
  Walk w;
  for (size_t i = 0; i < frames.size(); ++i) walk_stream(trial_frame(frames, i, cfg).stream, w);
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

struct Gain {
  double total = 0;
  std::string detail;  // each light's (diffuse + specular), for the series' reason
};

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

// What the term widths save: read from the final unit, whose span setup decides the layout.
std::string packing_why(const UnitConfig& cfg) {
  const CoefLayout layout = CoefLayout::of(cfg);
  int bits = 0;
  for (int t = 0; t < kTermsPerSeries; ++t) bits += cfg.coef_term_bits(t);
  return std::to_string(bits) + " bits per series, a triangle's " +
         std::to_string(cfg.series_per_triangle()) + " series in " + std::to_string(layout.words) +
         " payload words (" + std::to_string(cfg.series_per_triangle() * kTermsPerSeries) +
         " unpacked)";
}

// The throughput structure's reasons (derive/throughput_choice.h), in config_to_json's order;
// material_buffers and start_depth are listed whether or not the JSON writes them (it leaves
// out their defaults), so a later choice can replace every one (rechoose_throughput).
std::vector<FieldReason> throughput_reasons(const UnitConfig& cfg, const ThroughputChoice& t) {
  const std::string only = " (throughput only: pixels do not depend on it)";
  std::vector<FieldReason> r = {
      {"port_words", std::to_string(cfg.port_words), t.port_words + only},
      {"tri_queue", std::to_string(cfg.tri_queue), t.tri_queue},
      {"material_buffers", std::to_string(cfg.material_buffers), t.material_buffers},
      {"span_setup", to_string(cfg.span_setup), t.span_setup}};
  if (cfg.host_setup())
    r.push_back({"start_depth", std::to_string(cfg.start_depth),
                 "the start bank's entries: " + t.start_depth});
  return r;
}

// The specular line's value: the unit as the CLI names it, with its output format.
std::string specular_value(const UnitConfig& cfg) {
  return cfg.specular.describe() + (cfg.specular.kind == SpecularUnitKind::kNone
                                        ? std::string()
                                        : " out=" + cfg.specular.out.to_string());
}

// The specular line's note on a Schlick or W_m unit's timing; "" for other units.
constexpr const char* kTimingNote = "; timing ";
std::string timing_why(const ThroughputChoice& t) {
  return t.timing.empty() ? "" : kTimingNote + t.timing + " (throughput only: same bits)";
}

// The budget's reason, then one per field in config_to_json's order, each value as it writes it.
std::vector<FieldReason> field_reasons(const UnitConfig& cfg, const Budget& budget,
                                       const FieldWhys& why, const ThroughputChoice& throughput) {
  const auto json = nlohmann::json::parse(config_to_json(cfg));
  std::vector<FieldReason> reasons;
  reasons.push_back({"budget", fmt(budget.lsb) + " LSB",
                     "from " + budget.from +
                         "; Taylor error keeps it in setup, the "
                         "fixed-point error gets budget/4 for drift, budget/4 for "
                         "coefficient rounding, 3/16 for the colour words and 1/16 for the "
                         "specular output on top"});
  auto reason = [&json, &reasons](const char* field, const std::string& text) {
    const auto& value = json.at(field);
    reasons.push_back({field, value.is_string() ? value.get<std::string>() : value.dump(), text});
  };
  reason("channels", why.channels);
  reason("lights", why.lights);
  reason("xy_bits", why.xy_bits);
  if (json.contains("offset_bits")) reason("offset_bits", why.offset_bits);
  reason("coef", why.coef);
  reason("coef_term_iwl", why.coef_term_iwl + "; " + packing_why(cfg));
  reason("series", why.series);
  reason("spec_colour", why.spec_colour);
  reason("out_bits", "as requested");
  for (FieldReason& r : throughput_reasons(cfg, throughput)) reasons.push_back(std::move(r));
  reasons.push_back({"diffuse_colour", to_string(cfg.diffuse_colour), why.diffuse_colour});
  reasons.push_back(
      {"specular", specular_value(cfg), why.specular + why.specular_out + timing_why(throughput)});
  return reasons;
}

}  // namespace

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

// Every field for one specular substitute (options.ideal_substitute); derive_config below tries
// the fallbacks.
DerivedConfig derive_widths(const FrameSet& frames, const DeriveOptions& options) {
  const std::vector<SceneInfo> scenes = load_scenes(frames);
  const Budget budget = choose_budget(scenes, options);
  DerivedConfig out;
  ConfigMeasurements& ms = out.measured;
  set_budget(budget.lsb, ms);
  UnitConfig& cfg = out.config;  // quantization and overflow rules and unit widths: the defaults
  cfg.out_bits = options.out_bits;
  FieldWhys why;
  why.channels = derive_channels(scenes, cfg);
  why.lights = derive_lights(scenes, cfg);
  why.diffuse_colour = derive_diffuse_colour(options, cfg);
  const SpecularChoice specular = choose_specular_unit(scenes, options, cfg);
  out.substitute = specular.substitute;
  why.specular = specular.why;
  why.xy_bits = derive_xy_bits(scenes, cfg, ms);
  why.spec_colour = derive_spec_colour(scenes, ms, cfg);
  why.specular_out = derive_specular_out(scenes, ms, cfg);
  const Walk w = measure_on_trial_unit(frames, cfg);
  record_walk(w, ms);
  why.offset_bits = derive_offset_bits(w, cfg);
  why.series = derive_series(scenes, w, ms, cfg);
  why.coef = derive_coef(w, ms, cfg);
  why.coef_term_iwl = derive_term_widths(w, cfg);
  cfg.validate();
  const ThroughputChoice throughput = choose_throughput(frames, options, cfg);
  cfg = throughput.config;
  out.cycles_misses = throughput.misses;
  out.cycles = throughput.cycles;
  out.reasons = field_reasons(cfg, budget, why, throughput);
  return out;
}

namespace {

// The largest error of `config` over the scenes, in output codes.
int max_code_error(const FrameSet& frames, const UnitConfig& config, const DeriveOptions& options) {
  (void)options;
  int worst = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    worst = std::max(worst, scene_error(frames.at(i), config).max_code_lsb);
  }
  return worst;
}

// The N.L gate's step (host/gate_flips.h): where the derived widths flip a scene's gate with an
// output over the budget, series and coef get the fraction bits that hold every scene's gate.
void hold_the_gate(const FrameSet& frames, const DeriveOptions& options, DerivedConfig& d) {
  int bits = 0;
  std::string why;
  (void)options;
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string& path = frames.path(i);
    const GateFlips f =
        measure_gate_flips(frames.at(i), d.config, code_budget(d.measured.budget_lsb));
    if (f.pixels == 0 || f.fix_bits <= bits) continue;  // fix_bits -1: no width holds it
    bits = f.fix_bits;
    why = "; +" + std::to_string(bits) +
          " fraction bits for the N.L gate: " + std::to_string(f.pixels) + " pixel(s) of " + path +
          " near the terminator flipped it against the widest formats, up to " +
          std::to_string(f.max_lsb) + " LSB off, and these hold it";
  }
  if (bits == 0) return;
  d.config = with_more_fraction_bits(d.config, bits);
  const auto json = nlohmann::json::parse(config_to_json(d.config));
  for (auto& r : d.reasons) {
    if (r.field != "series" && r.field != "coef") continue;
    r.value = json.at(r.field).get<std::string>();
    r.reason += why;
  }
}

// The throughput structure chosen again for d.config's widths: the gate's fraction bits widen
// the coefficient and start words, so the port may no longer carry them in time. Replaces the
// knobs, their reasons and the cycles misses.
void rechoose_throughput(const FrameSet& frames, const DeriveOptions& options, DerivedConfig& d) {
  const ThroughputChoice t = choose_throughput(frames, options, d.config);
  d.config = t.config;
  d.cycles_misses = t.misses;
  d.cycles = t.cycles;
  for (FieldReason& fresh : throughput_reasons(d.config, t)) {
    const auto at = std::find_if(d.reasons.begin(), d.reasons.end(),
                                 [&](const FieldReason& r) { return r.field == fresh.field; });
    if (at != d.reasons.end()) {
      *at = std::move(fresh);
    } else {  // start_depth, now with host setup: after span_setup
      const auto site = std::find_if(d.reasons.begin(), d.reasons.end(),
                                     [](const FieldReason& r) { return r.field == "span_setup"; });
      d.reasons.insert(site == d.reasons.end() ? site : site + 1, std::move(fresh));
    }
  }
  if (!d.config.host_setup()) {
    d.reasons.erase(std::remove_if(d.reasons.begin(), d.reasons.end(),
                                   [](const FieldReason& r) { return r.field == "start_depth"; }),
                    d.reasons.end());
  }
  for (FieldReason& r : d.reasons) {
    if (r.field != "specular") continue;
    r.reason = r.reason.substr(0, r.reason.find(kTimingNote)) + timing_why(t);
    r.value = specular_value(d.config);
  }
}

}  // namespace

std::string Pipelining::describe() const {
  std::string s = "combine_stages " + std::to_string(combine_stages);
  if (square_stages != 1) s += ", square_stages " + std::to_string(square_stages);
  return s;
}

namespace {
bool squares_pipelined(const UnitConfig& unit) {
  return unit.specular.kind == SpecularUnitKind::kWpow &&
         unit.specular.wpow.timing == UnitTiming::kPipelined &&
         WpowUnit::stages(unit.specular.wpow) > 0;
}
}  // namespace

Pipelining pipelining_of(const UnitConfig& unit) {
  return {unit.combine_stages, squares_pipelined(unit) ? unit.specular.wpow.square_stages : 1};
}

std::vector<Pipelining> pipelining_ladder(const UnitConfig& unit) {
  std::vector<Pipelining> ladder = {{0, 1}, {1, 1}, {2, 1}};
  if (squares_pipelined(unit)) ladder.push_back({2, 2});
  return ladder;
}

void pipeline_unit(const FrameSet& frames, const DeriveOptions& options, const Pipelining& p,
                   const std::string& why, DerivedConfig& derived) {
  derived.config.combine_stages = p.combine_stages;
  if (derived.config.specular.kind == SpecularUnitKind::kWpow)
    derived.config.specular.wpow.square_stages = p.square_stages;
  derived.config.validate();
  rechoose_throughput(frames, options, derived);
  derived.reasons.erase(
      std::remove_if(derived.reasons.begin(), derived.reasons.end(),
                     [](const FieldReason& r) { return r.field == "combine_stages"; }),
      derived.reasons.end());
  derived.reasons.push_back({"combine_stages", std::to_string(p.combine_stages), why});
}

namespace {

// derive_widths, with the gate held (and the throughput structure chosen for its widths).
DerivedConfig derive_held(const FrameSet& frames, const DeriveOptions& options) {
  DerivedConfig d = derive_widths(frames, options);
  if (!options.hold_gate) return d;
  const std::string before = config_to_json(d.config);
  hold_the_gate(frames, options, d);
  if (config_to_json(d.config) != before) rechoose_throughput(frames, options, d);
  return d;
}

bool substituted(const DerivedConfig& d, const DeriveOptions& options) {
  return d.substitute && d.config.specular.kind == options.ideal_substitute.kind;
}

// The units tried after the first: the ideal stand-ins, or the named kind's other fields.
std::vector<SpecularConfig> units_to_try(const DerivedConfig& first, const DeriveOptions& options) {
  if (options.specular_trial) return {};  // a search of its own is under way
  if (substituted(first, options)) return options.ideal_fallbacks;
  if (!options.search_named_units || first.substitute) return {};
  std::vector<SpecularConfig> rest = named_unit_candidates(first.config.specular.kind);
  if (!rest.empty()) rest.erase(rest.begin());  // the defaults: the first unit derived
  return rest;
}

// One unit tried: its derivation, its error and its cycles on the scenes (the worst of each).
struct UnitTrial {
  DerivedConfig derived;
  int error = 0;
  SceneCycles cycles;
  std::string describe() const {
    return derived.config.specular.describe() + " " + std::to_string(error) + " LSB at " +
           fmt(cycles.per_pixel()) + " cycles/px";
  }
};

UnitTrial try_unit(const FrameSet& frames, const DeriveOptions& options, DerivedConfig derived) {
  UnitTrial t;
  t.error = max_code_error(frames, derived.config, options);
  for (size_t i = 0; i < frames.size(); ++i) {
    const SceneCycles c = derived.cycles.size() == frames.size()
                              ? derived.cycles[i]
                              : scene_cycles(frames.at(i), derived.config);
    if (c.per_pixel() >= t.cycles.per_pixel()) t.cycles = c;
  }
  t.derived = std::move(derived);
  return t;
}

bool exact_pow_misses(const FrameSet& frames, const DeriveOptions& options, const UnitConfig& unit,
                      int allowed) {
  UnitConfig exact = unit;
  exact.specular.kind = SpecularUnitKind::kIdeal;
  return max_code_error(frames, exact, options) > allowed;
}

// Budget first: a unit within the budget is taken unless it costs more cycles than the target
// and the first unit's plus 1 % (and 2 cycles of pipeline fill per frame, which decide a frame
// of a few pixels). When none within the budget stays within that, the first within the budget
// is taken all the same and the cycles it trades are stated.
double cycles_allowance(const DeriveOptions& options, const SceneCycles& first) {
  const double pixels = std::max<double>(1.0, static_cast<double>(first.pixels));
  return std::max(options.max_cycles_per_pixel, first.per_pixel() * 1.01 + 2.0 / pixels);
}

// Tries `units` in order; `best` (the first unit, over the budget) becomes the unit taken. Returns
// the note on the specular line: what was tried, what was taken and what it traded.
std::string search_units(const FrameSet& frames, const DeriveOptions& options,
                         const std::vector<SpecularConfig>& units, int allowed, UnitTrial& best,
                         std::string& tried) {
  const UnitTrial first = best;
  const double allowance = cycles_allowance(options, first.cycles);
  std::optional<UnitTrial> within, slow;
  UnitTrial closest = first, last = first;
  // Candidates are tried a batch at a time, one per thread, and read in order: the one taken and
  // the text are those of a one-by-one search whatever the thread count.
  const size_t batch = static_cast<size_t>(thread_count(options.threads));
  std::vector<UnitTrial> trials;
  for (size_t i = 0; i < units.size() && !within; ++i) {
    if (i % batch == 0) {
      const size_t n = std::min(batch, units.size() - i);
      trials = parallel_map<UnitTrial>(n, options.threads, [&](size_t k) {
        DeriveOptions o = options;
        o.specular_trial = units[i + k];
        if (first.derived.substitute) o.ideal_substitute = units[i + k];
        return try_unit(frames, o, derive_held(frames, o));
      });
    }
    UnitTrial& t = trials[i % batch];
    tried += ", " + t.describe();
    if (t.error < closest.error) closest = t;
    if (t.derived.config.specular.kind == closest.derived.config.specular.kind) last = t;
    if (t.error > allowed) continue;
    if (t.cycles.per_pixel() <= allowance) {
      within = std::move(t);
      continue;
    }
    tried += " (over " + fmt(allowance) + ")";
    if (!slow) slow = std::move(t);
  }
  const std::string budget = std::to_string(allowed) + " LSB";
  if (within) {
    best = *within;
    return "measured against the budget on the scenes, smallest first: " + tried +
           " (the first within " + budget + " and " + fmt(allowance) + " cycles/px)";
  }
  if (slow) {
    best = *slow;
    return "measured against the budget on the scenes, smallest first: " + tried +
           "; budget first: " + slow->derived.config.specular.describe() + " is within " + budget +
           " and trades " + fmt(slow->cycles.per_pixel() - first.cycles.per_pixel()) +
           " cycles/px against the first";
  }
  best = closest;
  return "no unit tried meets the " + budget + " budget on the scenes: " + tried +
         "; the closest, " + closest.derived.config.specular.describe() + " at " +
         std::to_string(closest.error) + " LSB, is kept. What limits it is the " +
         to_string(closest.derived.config.specular.kind) +
         " unit's function, not the formats (exact pow on the first unit's formats is within " +
         budget + "): its widest fields tried, " + last.derived.config.specular.describe() +
         ", reach " + std::to_string(last.error) + " LSB";
}

}  // namespace

DerivedConfig derive_config(const FrameSet& frames, const DeriveOptions& options) {
  DerivedConfig first = derive_held(frames, options);
  const std::vector<SpecularConfig> rest = units_to_try(first, options);
  if (rest.empty() && !substituted(first, options)) return first;
  // The specular unit must meet the budget on the scenes (measured, not bounded: a unit's
  // approximation of t^n is not in the width rules), else the next candidate, each with the
  // widths derived for it. The reason lists every unit tried.
  const int allowed = code_budget(first.measured.budget_lsb);
  UnitTrial best = try_unit(frames, options, first);
  std::string tried = best.describe();
  std::string note;
  if (best.error <= allowed) {
    note = "measured against the budget on the scenes: " + tried + " (within " +
           std::to_string(allowed) + " LSB)";
  } else if (exact_pow_misses(frames, options, first.config, allowed)) {
    // No unit will meet it: the formats, the Taylor setup or the N.L gate do not (shadesim
    // config says which and exits 1).
    note = "misses the " + fmt(first.measured.budget_lsb) + " LSB budget on the scenes (" + tried +
           "), and so does exact pow on its formats: no other unit is tried";
  } else {
    note = search_units(frames, options, rest, allowed, best, tried);
  }
  for (auto& r : best.derived.reasons) {
    if (r.field == "specular") r.reason += "; " + note;
  }
  return best.derived;
}

PrepareKey prepare_key(const DeriveOptions& options) {
  return {options.budget_lsb, options.max_depth, options.out_bits};
}

void check_derive_options(const std::vector<std::string>& scene_paths,
                          const DeriveOptions& options) {
  if (scene_paths.empty()) throw std::invalid_argument("derive_config: no scenes given");
  if (options.budget_lsb) check_budget(*options.budget_lsb);
}

DerivedConfig derive_config(const std::vector<std::string>& scene_paths,
                            const DeriveOptions& options) {
  check_derive_options(scene_paths, options);
  PreparedScenes frames;
  return derive_config(FrameSet(frames, scene_paths, prepare_key(options)), options);
}

}  // namespace shadesim
