#include "derive/accuracy_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "derive/budget.h"
#include "derive/miss_causes.h"
#include "derive/trial_unit.h"
#include "derive/width_rules.h"
#include "host/gate_flips.h"
#include "host/scene_error.h"
#include "model/command_stream.h"

namespace shadesim {
namespace {

// One format warning, and the unit with the width it names (none where it names no width that
// holds): what accuracy_warnings re-shades to check the warning as a cause of a miss.
struct Finding {
  std::string text;
  std::optional<UnitConfig> fixed;
};

// `f` with its integer bits set to `iwl`, its fraction bits kept.
FixedFormat with_iwl(FixedFormat f, int iwl) {
  f.wl += iwl - f.iwl;
  f.iwl = iwl;
  return f;
}

// The longest span the series format's drift bound allows within `share_lsb` output LSBs at
// `gain` (the inverse of drift_fraction_bits).
int longest_span_within_drift(const FixedFormat& series, double gain, double share_lsb,
                              int out_bits) {
  const double allowed = share_lsb * std::ldexp(1.0, -out_bits);
  const double lsb =
      std::ldexp(series.quant == Quantization::kRoundNearest ? 0.5 : 1.0, -series.frac_bits());
  auto fits = [&](int len) { return gain * (1.0 + len * (len - 1.0) / 2.0) * lsb <= allowed; };
  int longest = 0;
  for (int len = 1; len <= (1 << 16) && fits(len); len *= 2) longest = len;
  // Refine between the last power of two that fits and the next.
  for (int len = longest + 1; len < 2 * std::max(1, longest) && fits(len); ++len) longest = len;
  return longest;
}

// Fewest signed integer bits holding [lo, hi].
int signed_bits(double lo, double hi) {
  int iwl = 1;
  while (iwl < 62 && (lo < -std::ldexp(1.0, iwl - 1) || hi >= std::ldexp(1.0, iwl - 1))) ++iwl;
  return iwl;
}

std::optional<Finding> series_range_warning(const ConfigMeasurements& m, const UnitConfig& unit) {
  const double half = std::ldexp(1.0, unit.series.iwl - 1);
  const double hi = std::max(m.series_max, m.product_max);
  if (m.series_min >= -half && hi < half) return std::nullopt;
  const int need = std::max(2, signed_bits(m.series_min, hi));
  UnitConfig fixed = unit;
  fixed.series = with_iwl(unit.series, need);
  fixed.coef = with_iwl(unit.coef, std::max(unit.coef.iwl, need));
  fixed.coef_term_iwl.clear();
  const std::string text = fmt::format(
      "series {}: series values at the pixels reach [{:.4g}, {:.4g}]{}, beyond its range "
      "[-{:g}, {:g}): pixels there wrap or saturate; {} integer bits would hold them (e.g. "
      "--series s{}.{})",
      unit.series.to_string(), m.series_min, m.series_max,
      m.product_max >= half ? fmt::format(" and colour products {:.4g}", m.product_max) : "", half,
      half, need, need, unit.series.frac_bits());
  return Finding{text, fixed};
}

// Colour words at the top of spec_colour: the encoder saturated them.
std::optional<Finding> colour_warning(const ConfigMeasurements& m, const UnitConfig& unit,
                                      const CommandStream& stream) {
  const bool read = unit.specular.kind != SpecularUnitKind::kNone || unit.diffuse_multiply();
  const FixedFormat& f = unit.spec_colour;
  const double top = std::ldexp(static_cast<double>(f.raw_max()), -f.frac_bits());
  if (!read || m.colour_max <= top) return std::nullopt;
  size_t words = 0, saturated = 0;
  for (const Command& cmd : stream.commands) {
    if (const auto* mat = std::get_if<MaterialCmd>(&cmd)) {
      for (const auto* list : {&mat->spec_colour, &mat->diffuse_colour}) {
        words += list->size();
        saturated += static_cast<size_t>(std::count(list->begin(), list->end(), f.raw_max()));
      }
    }
  }
  int iwl = f.iwl;
  while (std::ldexp(1.0, iwl) - std::ldexp(1.0, -f.frac_bits()) < m.colour_max) ++iwl;
  UnitConfig fixed = unit;
  fixed.spec_colour = with_iwl(f, iwl);
  const std::string text = fmt::format(
      "spec_colour {}: the colour words (ks_c L_c{}) reach {:.4g}, above its top {:.4g}: {} of "
      "{} colour words in the stream saturate, so lit pixels are too dark; u{}.{} would hold "
      "them (--spec-colour)",
      f.to_string(), unit.diffuse_multiply() ? ", kd_c L_c" : "", m.colour_max, top, saturated,
      words, iwl, f.frac_bits());
  return Finding{text, fixed};
}

std::optional<Finding> drift_warning(const ConfigMeasurements& m, const UnitConfig& unit,
                                     const CommandStream& stream) {
  const int within =
      longest_span_within_drift(unit.series, m.gain, m.drift_share_lsb, unit.out_bits);
  size_t beyond = 0;
  int longest = 0;
  for (const Command& cmd : stream.commands) {
    if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      longest = std::max(longest, s->length);
      if (s->length > within) ++beyond;
    }
  }
  if (beyond == 0) return std::nullopt;
  const int frac = drift_fraction_bits(longest, m.gain, m.drift_share_lsb, unit.out_bits,
                                       unit.series.quant == Quantization::kRoundNearest);
  UnitConfig fixed = unit;
  if (frac > unit.series.frac_bits())
    fixed = with_more_fraction_bits(unit, frac - unit.series.frac_bits());
  const std::string text = fmt::format(
      "series {}: {} span(s) longer than {} px (the longest {}) exceed its drift bound within "
      "{:g} LSB (budget/4, gain {:.4g}): {} series fraction bits would hold them",
      unit.series.to_string(), beyond, within, longest, m.drift_share_lsb, m.gain, frac);
  return Finding{text, fixed};
}

// Pixels whose N.L gate flips over the budget, with the fraction bits that hold them.
std::optional<Finding> gate_flip_warning(const PreparedScene& frame, const UnitConfig& unit,
                                         double budget_lsb) {
  const GateFlips f = measure_gate_flips(frame, unit, code_budget(budget_lsb));
  if (f.pixels == 0) return std::nullopt;
  const std::string w = fmt::format(
      "{} pixel(s) near the terminator open or close the specular N.L gate against the widest "
      "formats (their N.L is within the series' truncation and the coefficients' rounding of "
      "0), up to {} LSB off, over the {:g} LSB budget: ",
      f.pixels, f.max_lsb, budget_lsb);
  if (f.fix_bits < 0)
    return Finding{w + "no narrower series and coef than the widest hold them", std::nullopt};
  return Finding{w + fmt::format("{} more fraction bits in series and coef ({}, {}) hold them",
                                 f.fix_bits, f.fixed.series.to_string(), f.fixed.coef.to_string()),
                 f.fixed};
}

// The scene's format findings on `unit` (format_warnings' texts).
std::vector<Finding> format_findings(const PreparedScene& frame, const UnitConfig& unit,
                                     const CommandStream& stream) {
  std::optional<ConfigMeasurements> measured;
  try {
    measured = measure_scene_on(frame, unit);
  } catch (const std::exception& e) {
    return {{std::string("could not measure the scene against the unit's formats: ") + e.what(),
             std::nullopt}};
  }
  const ConfigMeasurements& m = *measured;
  std::vector<Finding> out;
  const auto range = series_range_warning(m, unit);
  if (range) out.push_back(*range);
  if (auto w = colour_warning(m, unit, stream)) out.push_back(*w);
  if (auto w = drift_warning(m, unit, stream)) out.push_back(*w);
  // Out of range, the series wraps or saturates everywhere: that warning says it all.
  if (!range) {
    if (auto w = gate_flip_warning(frame, unit, m.budget_lsb)) out.push_back(*w);
  }
  return out;
}

// A finding on an image over the budget names a cause of the miss: the frame re-shaded with
// the width it names says whether that alone meets the budget.
std::string verified(const PreparedScene& frame, const Finding& f, int allowed) {
  if (!f.fixed) return f.text;
  int e = 0;
  try {
    f.fixed->validate();
    e = scene_error(frame, *f.fixed).max_code_lsb;
  } catch (const std::exception& ex) {
    return f.text + "; that width could not be re-shaded: " + ex.what();
  }
  return f.text + fmt::format("; re-shaded with it the frame is {} LSB{}", e,
                              e <= allowed ? ", within the budget"
                                           : ", still over the budget: not the whole miss");
}

}  // namespace

UnitConfig lossless_formats(const UnitConfig& unit, double colour_max) {
  UnitConfig wide = unit;
  wide.series = FixedFormat{52, 12, true, unit.series.quant, unit.series.overflow};
  wide.coef = FixedFormat{60, 24, true, Quantization::kRoundNearest, Overflow::kSaturate};
  wide.coef_term_iwl.clear();
  int colour_iwl = 1;
  while (colour_iwl < 24 && std::ldexp(1.0, colour_iwl) <= colour_max) ++colour_iwl;
  wide.spec_colour = FixedFormat{colour_iwl + 24, colour_iwl, false, Quantization::kRoundNearest,
                                 Overflow::kSaturate};
  wide.specular.out = FixedFormat{25, 1, false, Quantization::kTruncate, Overflow::kSaturate};
  return wide;
}

std::vector<std::string> format_warnings(const PreparedScene& frame, const UnitConfig& unit,
                                         const CommandStream& stream) {
  std::vector<std::string> out;
  for (const Finding& f : format_findings(frame, unit, stream)) out.push_back(f.text);
  return out;
}

std::string explain_miss(const PreparedScene& frame, const UnitConfig& unit,
                         const ErrorStats& error) {
  return explain_miss_cause(frame, unit, error).text;
}

std::vector<std::string> accuracy_warnings(const PreparedScene& frame, const UnitConfig& unit,
                                           const CommandStream& stream, const ErrorStats& error) {
  const double budget = frame.key().budget_lsb.value_or(frame.scene().error_budget_lsb);
  const bool over = error.pixels > 0 && error.max_code_lsb > code_budget(budget);
  std::vector<std::string> out;
  for (const Finding& f : format_findings(frame, unit, stream))
    out.push_back(over ? verified(frame, f, code_budget(budget)) : f.text);
  if (over) {
    try {
      out.push_back(explain_miss(frame, unit, error));
    } catch (const std::exception& e) {
      out.push_back(
          fmt::format("max {} LSB over the {:g} LSB budget; its cause could not be "
                      "measured: {}",
                      error.max_code_lsb, budget, e.what()));
    }
  }
  return out;
}

}  // namespace shadesim
