// Where a unit's widths cannot hold a scene, say so (issue 23: never a silently wrong image).
// The scene is measured as `shadesim config` measures it (a trial unit that loses nothing:
// series values at every pixel, the longest span, the gain of the series into an output
// channel), and the unit's own formats are checked against what those numbers need:
//   series range   values beyond the series format's integer range wrap or saturate: wrong
//                  pixels wherever they occur (an overbright light, say);
//   drift          spans longer than the series fraction bits' drift bound allows within a
//                  quarter of the budget (a very wide image at narrow widths);
//   N.L gate       pixels near the terminator whose specular gate flips against the widest
//                  formats with an output over the budget (host/gate_flips.h).
// Each warning names the width that would hold the scene.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "host/frame.h"
#include "host/gate_flips.h"
#include "host/scene_config.h"
#include "model/command_stream.h"

namespace shadesim {

// The longest span the series format's drift bound allows within `share_lsb` output LSBs at
// `gain` (the inverse of drift_fraction_bits).
inline int longest_span_within_drift(const FixedFormat& series, double gain, double share_lsb,
                                     int out_bits) {
  const double allowed = share_lsb * std::ldexp(1.0, -out_bits);
  const double lsb =
      std::ldexp(series.quant == Quantization::kRoundNearest ? 0.5 : 1.0, -series.frac_bits());
  int longest = 0;
  for (int len = 1; len <= (1 << 16); len *= 2) {
    const double steps = 1.0 + len * (len - 1.0) / 2.0;
    if (gain * steps * lsb > allowed) break;
    longest = len;
  }
  // Refine between the last power of two that fits and the next.
  for (int len = longest + 1; len < 2 * std::max(1, longest); ++len) {
    const double steps = 1.0 + len * (len - 1.0) / 2.0;
    if (gain * steps * lsb > allowed) break;
    longest = len;
  }
  return longest;
}

// Pixels whose N.L gate flips over the budget, with the fraction bits that hold them.
inline std::optional<std::string> gate_flip_warning(const PreparedFrame& frame,
                                                    const UnitConfig& unit, double budget_lsb) {
  const GateFlips f = measure_gate_flips(frame, unit, code_budget(budget_lsb));
  if (f.pixels == 0) return std::nullopt;
  std::string w = std::to_string(f.pixels) +
                  " pixel(s) near the terminator open or close the specular N.L gate against the "
                  "widest formats (their N.L is within the series' truncation and the "
                  "coefficients' rounding of 0), up to " +
                  std::to_string(f.max_lsb) + " LSB off, over the " +
                  fmt::format("{:g}", budget_lsb) + " LSB budget: ";
  if (f.fix_bits < 0) {
    return w + "no narrower series and coef than the widest hold them";
  }
  return w + std::to_string(f.fix_bits) + " more fraction bits in series and coef (" +
         f.fixed.series.to_string() + ", " + f.fixed.coef.to_string() + ") hold them";
}

inline std::vector<std::string> accuracy_warnings(const std::string& scene_path,
                                                  const UnitConfig& unit,
                                                  std::optional<double> budget_lsb, int max_depth,
                                                  const PreparedFrame& frame) {
  const CommandStream& stream = frame.encoded.stream;
  DeriveOptions d;
  d.budget_lsb = budget_lsb;
  d.out_bits = unit.out_bits;
  d.max_depth = max_depth;
  // Measured with the unit's own specular unit (its plan scales the specular series): a scene
  // naming ideal keeps the unit's, and no stand-in is tried.
  d.ideal_substitute = unit.specular;
  d.ideal_fallbacks.clear();
  d.hold_gate = false;  // measured below, on the unit itself
  std::optional<DerivedConfig> needed;
  try {
    needed = derive_config({scene_path}, d);
  } catch (const std::exception& e) {
    return {std::string("could not measure the scene against the unit's widths: ") + e.what()};
  }
  const ConfigMeasurements& m = needed->measured;
  std::vector<std::string> out;
  const double half = std::ldexp(1.0, unit.series.iwl - 1);
  const bool out_of_range = m.series_min < -half || m.series_max >= half;
  if (out_of_range) {
    out.push_back("series values at the pixels reach [" + std::to_string(m.series_min) + ", " +
                  std::to_string(m.series_max) + "], beyond " + unit.series.to_string() +
                  "'s range [-" + std::to_string(half) + ", " + std::to_string(half) +
                  "): pixels there are wrong; " + std::to_string(needed->config.series.iwl) +
                  " integer bits would hold them (e.g. --series s" +
                  std::to_string(needed->config.series.iwl) + "." +
                  std::to_string(unit.series.frac_bits()) + ")");
  }
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
  if (beyond > 0) {
    const int frac = drift_fraction_bits(longest, m.gain, m.drift_share_lsb, unit.out_bits,
                                         unit.series.quant == Quantization::kRoundNearest);
    out.push_back(std::to_string(beyond) + " span(s) longer than " + std::to_string(within) +
                  " px (the longest " + std::to_string(longest) + ") exceed the drift bound of " +
                  unit.series.to_string() + " within " + std::to_string(m.drift_share_lsb) +
                  " LSB (budget/4, gain " + std::to_string(m.gain) + "): " + std::to_string(frac) +
                  " series fraction bits would hold them");
  }
  // Out of range, the series wraps or saturates everywhere: that warning says it all.
  if (!out_of_range) {
    if (auto w = gate_flip_warning(frame, unit, m.budget_lsb)) out.push_back(*w);
  }
  return out;
}

}  // namespace shadesim
