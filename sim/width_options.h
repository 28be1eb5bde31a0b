// The unit's widths as command-line options, shared by every subcommand that builds a unit.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "model/unit_config.h"

namespace shadesim {

struct WidthOptions {
  UnitConfig defaults;
  std::string coef = defaults.coef.to_string();
  std::string series = defaults.series.to_string();
  std::string spec_colour = defaults.spec_colour.to_string();
  std::string spec_out = defaults.specular.out.to_string();
  int out_bits = defaults.out_bits;
  int xy_bits = defaults.xy_bits;
  // Specular unit widths and choices (model/specular_config.h).
  int lut_addr_bits = defaults.specular.lut.addr_bits;
  int lut_entry_bits = defaults.specular.lut.entry_bits;
  int lut_interp_bits = defaults.specular.lut.interp_bits;
  std::string lut_index = to_string(defaults.specular.lut.index);
  std::string lut_addressing = to_string(defaults.specular.lut.addressing);
  int schlick_quotient_bits = defaults.specular.schlick.quotient_bits;
  std::string schlick_timing = to_string(defaults.specular.schlick.timing);
  int wpow_m = defaults.specular.wpow.max_m;
  int wpow_bits = defaults.specular.wpow.base_bits;
  std::string wpow_timing = to_string(defaults.specular.wpow.timing);
  std::string fit = to_string(defaults.specular.wpow.fit);

  UnitConfig to_config() const {
    UnitConfig c = defaults;
    c.coef = parse_fixed_format(coef, "--coef");
    c.series = parse_fixed_format(series, "--series");
    c.spec_colour = parse_fixed_format(spec_colour, "--spec-colour");
    c.specular.out = parse_fixed_format(spec_out, "--spec-out");
    c.out_bits = out_bits;
    c.xy_bits = xy_bits;
    auto& sp = c.specular;
    sp.lut.addr_bits = lut_addr_bits;
    sp.lut.entry_bits = lut_entry_bits;
    sp.lut.interp_bits = lut_interp_bits;
    sp.lut.index = parse_lut_index(lut_index, "--lut-index");
    sp.lut.addressing = parse_lut_addressing(lut_addressing, "--lut-addressing");
    sp.schlick.quotient_bits = schlick_quotient_bits;
    sp.schlick.timing = parse_unit_timing(schlick_timing, "--schlick-timing");
    sp.wpow.max_m = wpow_m;
    sp.wpow.base_bits = wpow_bits;
    sp.wpow.timing = parse_unit_timing(wpow_timing, "--wpow-timing");
    const FitObjective f = parse_fit_objective(fit, "--fit");
    sp.wpow.fit = f;
    sp.schlick.fit = f;
    sp.lut.fit = f;
    c.validate();
    return c;
  }
};

// The option groups add_width_options fills (--config excludes every option in them).
constexpr const char* kWidthGroup = "Widths (s|u<integer bits incl. sign>.<fraction bits>[:trn|:rnd][:sat|:wrap])";
constexpr const char* kUnitWidthGroup = "Specular unit widths (see shadesim spec-error for their error and cost)";

inline void add_width_options(CLI::App& sub, WidthOptions& w) {
  const char* group = kWidthGroup;
  sub.add_option("--coef", w.coef, "triangle Taylor coefficient format")->capture_default_str()->group(group);
  sub.add_option("--series", w.series, "forward-difference accumulator format")->capture_default_str()->group(group);
  sub.add_option("--spec-colour", w.spec_colour, "specular colour format")->capture_default_str()->group(group);
  sub.add_option("--spec-out", w.spec_out, "specular unit output format")->capture_default_str()->group(group);
  sub.add_option("--out-bits", w.out_bits, "output bits per channel")->capture_default_str()->group(group);
  sub.add_option("--xy-bits", w.xy_bits, "screen coordinate bits")->capture_default_str()->group(group);
  const char* unit = kUnitWidthGroup;
  sub.add_option("--lut-addr-bits", w.lut_addr_bits, "LUT: address bits A (2^A entries)")->capture_default_str()->group(unit);
  sub.add_option("--lut-entry-bits", w.lut_entry_bits, "LUT: entry bits B")->capture_default_str()->group(unit);
  sub.add_option("--lut-interp-bits", w.lut_interp_bits, "LUT: interpolation fraction bits (0 = off)")->capture_default_str()->group(unit);
  sub.add_option("--lut-index", w.lut_index, "LUT: truncate|nearest")->capture_default_str()->group(unit);
  sub.add_option("--lut-addressing", w.lut_addressing, "LUT: per-exponent (reload per material) | shared")->capture_default_str()->group(unit);
  sub.add_option("--schlick-quotient-bits", w.schlick_quotient_bits, "Schlick: quotient bits Q (divider iterations)")->capture_default_str()->group(unit);
  sub.add_option("--schlick-timing", w.schlick_timing, "Schlick: iterative (Q cycles/pixel) | pipelined")->capture_default_str()->group(unit);
  sub.add_option("--wpow-m", w.wpow_m, "W_m: m (4, 8 or 16)")->capture_default_str()->group(unit);
  sub.add_option("--wpow-bits", w.wpow_bits, "W_m: fraction bits B of the base and squares")->capture_default_str()->group(unit);
  sub.add_option("--wpow-timing", w.wpow_timing, "W_m: pipelined | iterative")->capture_default_str()->group(unit);
  sub.add_option("--fit", w.fit, "per-exponent fit of zeta / n' / k: none | epicentre | absolute")->capture_default_str()->group(unit);
}

}  // namespace shadesim
