// The unit's widths as command-line options, shared by every subcommand that builds a unit.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/specular_units.h"
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
  int offset_bits = defaults.offset_bits;
  // Specular unit fields by command-line option (model/specular_units.h): the text as given,
  // parsed in to_config. Fields sharing an option (--fit) are set together.
  std::map<std::string, std::string> unit_fields = default_unit_fields(defaults.specular);

  static std::map<std::string, std::string> default_unit_fields(const SpecularConfig& s) {
    std::map<std::string, std::string> m;
    for (const SpecularUnitDescriptor& u : specular_units()) {
      for (const SpecularField& f : u.fields) {
        if (*f.cli != '\0') m.emplace(f.cli, f.text(s));
      }
    }
    return m;
  }

  // A width given without :sat or :wrap saturates (the form shadesim's own files write), where
  // SystemC's sc_fix would wrap: said on stderr, so the choice is never silent (issue 23).
  static void warn_without_overflow_suffix(const std::string& text, const std::string& fallback,
                                           const char* option) {
    if (text == fallback || text.find(":sat") != std::string::npos ||
        text.find(":wrap") != std::string::npos)
      return;
    std::cerr << "shadesim: note: " << option << ' ' << text
              << " has no overflow suffix, so it saturates (SystemC's sc_fix would wrap); write "
              << text << ":sat or " << text << ":wrap to choose\n";
  }

  UnitConfig to_config() const {
    UnitConfig c = defaults;
    warn_without_overflow_suffix(coef, defaults.coef.to_string(), "--coef");
    warn_without_overflow_suffix(series, defaults.series.to_string(), "--series");
    warn_without_overflow_suffix(spec_colour, defaults.spec_colour.to_string(), "--spec-colour");
    warn_without_overflow_suffix(spec_out, defaults.specular.out.to_string(), "--spec-out");
    c.coef = parse_fixed_format(coef, "--coef");
    c.series = parse_fixed_format(series, "--series");
    c.spec_colour = parse_fixed_format(spec_colour, "--spec-colour");
    c.specular.out = parse_fixed_format(spec_out, "--spec-out");
    c.out_bits = out_bits;
    c.xy_bits = xy_bits;
    c.offset_bits = offset_bits;
    // Every unit's options are checked, not only the unit the scene will select: a bad value
    // is named by its option here rather than later by its field.
    for (const SpecularUnitDescriptor& u : specular_units()) {
      for (const SpecularField& f : u.fields) {
        if (*f.cli == '\0') continue;
        const int v = f.parse(unit_fields.at(f.cli), f.cli);
        if (!f.in_range(v)) {
          throw std::invalid_argument(std::string(f.cli) + ": must be " + f.expected() + ", got " +
                                      unit_fields.at(f.cli));
        }
        f.set(c.specular, v);
      }
    }
    c.validate();
    return c;
  }
};

// The option groups add_width_options fills (--config excludes every option in them).
constexpr const char* kWidthGroup =
    "Widths (s|u<integer bits incl. sign>.<fraction bits>[:trn|:rnd][:sat|:wrap]; no suffix "
    "means :trn and :sat, unlike SystemC's sc_fix, which wraps: write :wrap for its meaning)";
constexpr const char* kUnitWidthGroup =
    "Specular unit widths (see shadesim spec-error for their error and cost)";

inline void add_width_options(CLI::App& sub, WidthOptions& w) {
  const char* group = kWidthGroup;
  sub.add_option("--coef", w.coef, "triangle Taylor coefficient format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--series", w.series, "forward-difference accumulator format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--spec-colour", w.spec_colour, "specular colour format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--spec-out", w.spec_out, "specular unit output format")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--out-bits", w.out_bits, "output bits per channel")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--xy-bits", w.xy_bits, "screen coordinate bits")
      ->capture_default_str()
      ->group(group);
  sub.add_option("--offset-bits", w.offset_bits,
                 "span setup's signed offset bits (a span's start from its triangle's origin); "
                 "the encoder re-origins triangles beyond them")
      ->capture_default_str()
      ->group(group);
  // One option per distinct flag of the unit table; an option that several units share (--fit)
  // comes after the units' own ones.
  std::vector<const SpecularField*> own, shared;
  std::map<std::string, int> uses;
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      if (*f.cli != '\0' && uses[f.cli]++ == 0) own.push_back(&f);
    }
  }
  for (const SpecularField* f : own) {
    if (uses[f->cli] > 1) shared.push_back(f);
  }
  own.erase(std::remove_if(own.begin(), own.end(),
                           [&](const SpecularField* f) { return uses[f->cli] > 1; }),
            own.end());
  own.insert(own.end(), shared.begin(), shared.end());
  for (const SpecularField* f : own) {
    const std::string help = std::string(f->help) + " (" + f->expected() + ")";
    sub.add_option(f->cli, w.unit_fields.at(f->cli), help)
        ->capture_default_str()
        ->type_name(f->is_enum() ? "TEXT" : "INT")
        ->group(kUnitWidthGroup);
  }
}

}  // namespace shadesim
