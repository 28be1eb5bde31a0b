// The unit's widths as plain values (what a command was given, as text), turned into a
// UnitConfig by to_config(). The command-line options that fill them: sim/cli/width_options.h.
#pragma once

#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

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

}  // namespace shadesim
