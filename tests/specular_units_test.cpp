// The specular unit table (model/specular_units.h) against the code that walks it: every field
// of every unit round-trips through the UnitConfig JSON, has a command-line option that sets
// it, reaches its Verilog parameter, and is refused out of range with an error naming it. The
// Verilog names and defaults are checked against rtl/shade_unit.sv's parameter list, read from
// the file, and a few slot timings against rtl/shade_pkg.sv's spec_latency written out by hand.
#include "model/specular_units.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "model/command_stream.h"
#include "model/cycle_model.h"
#include "model/rtl_parameters.h"
#include "model/unit_config_file.h"
#include "sim/width_options.h"

namespace shadesim {
namespace {

std::map<std::string, int64_t> as_map(const std::vector<VerilogParameter>& params) {
  std::map<std::string, int64_t> m;
  for (const auto& p : params) m[p.name] = p.value;
  return m;
}

// A config that selects `unit` (its other fields at their defaults).
UnitConfig on(const SpecularUnitDescriptor& unit) {
  UnitConfig c;
  c.specular.kind = unit.kind;
  return c;
}

// An accepted value of `f` other than its value in `c` (the field is then seen to change).
int other_value(const SpecularField& f, const SpecularConfig& c) {
  const int now = f.get(c);
  for (int v = f.hi; v >= f.lo; --v) {
    if (v != now && f.in_range(v)) return v;
  }
  ADD_FAILURE() << f.key << " has no second accepted value";
  return now;
}

// Out-of-range values of an integer field (below, above, and a non-power of two if it must be
// one).
std::vector<int> rejected_values(const SpecularField& f) {
  std::vector<int> v = {f.lo - 1, f.hi + 1};
  if (f.power_of_two) {
    for (int x = f.lo; x <= f.hi; ++x) {
      if (!f.in_range(x)) {
        v.push_back(x);
        break;
      }
    }
  }
  return v;
}

std::string json_value(const SpecularField& f, int v) {
  return f.is_enum() ? "\"" + f.value_name(v) + "\"" : std::to_string(v);
}

// {"specular": {"kind": UNIT, UNIT: {KEY: VALUE}}}
std::string overlay(const SpecularUnitDescriptor& u, const SpecularField& f,
                    const std::string& value) {
  return std::string(R"({"specular": {"kind": ")") + u.name + R"(", ")" + u.name + R"(": {")" +
         f.key + R"(": )" + value + "}}}";
}

// The error message of overlay_unit_config on `json` ("" if it does not throw).
std::string overlay_error(const std::string& json) {
  try {
    (void)overlay_unit_config(json, UnitConfig{}, "test.json");
  } catch (const UnitConfigFileError& e) {
    return e.what();
  }
  return "";
}

// to_config of the width options after parsing `args` (argv without the program name).
UnitConfig parse_cli(const std::vector<std::string>& args) {
  CLI::App app;
  WidthOptions w;
  add_width_options(app, w);
  std::vector<std::string> argv = args;
  std::reverse(argv.begin(), argv.end());  // CLI11's vector parse takes the arguments reversed
  app.parse(argv);
  return w.to_config();
}

std::string cli_error(const std::vector<std::string>& args) {
  try {
    (void)parse_cli(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const CLI::ParseError& e) {
    return std::string("CLI11: ") + e.what();
  }
  return "";
}

TEST(SpecularUnits, EveryKindHasOneRowWithUniqueNames) {
  std::set<std::string> names, verilog;
  std::set<int> codes;
  for (const SpecularUnitKind k : {SpecularUnitKind::kIdeal, SpecularUnitKind::kLut,
                                   SpecularUnitKind::kSchlick, SpecularUnitKind::kWpow}) {
    const SpecularUnitDescriptor& u = specular_unit(k);
    EXPECT_EQ(u.kind, k);
    EXPECT_TRUE(names.insert(u.name).second) << u.name;
    EXPECT_TRUE(codes.insert(u.verilog_kind).second) << u.name;
    EXPECT_EQ(find_specular_unit(u.name), &u);
    std::set<std::string> keys;
    for (const SpecularField& f : u.fields) {
      EXPECT_TRUE(keys.insert(f.key).second) << u.field_name(f) << " twice";
      if (*f.verilog) {
        EXPECT_TRUE(verilog.insert(f.verilog).second) << f.verilog << " twice";
      }
      EXPECT_LE(f.lo, f.hi) << u.field_name(f);
      EXPECT_TRUE(f.in_range(f.get(SpecularConfig{})))
          << u.field_name(f) << "'s default is out of range";
    }
  }
  EXPECT_EQ(specular_units().size(), 4u);
  EXPECT_EQ(find_specular_unit("nope"), nullptr);
  EXPECT_EQ(specular_unit_names(), "ideal, lut, schlick, wpow");
  EXPECT_EQ(specular_unit_names(true), "lut, schlick, wpow");
}

TEST(SpecularUnits, EveryFieldRoundTripsThroughJson) {
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      UnitConfig c = on(u);
      const int v = other_value(f, c.specular);
      f.set(c.specular, v);
      // Written by config_to_json, read back both as a stream header and as a config file.
      const std::string json = config_to_json(c);
      EXPECT_EQ(f.get(config_from_json(json, "test: ").specular), v)
          << u.field_name(f) << " in " << json;
      EXPECT_EQ(f.get(overlay_unit_config(json, UnitConfig{}, "test.json").specular), v)
          << u.field_name(f);
      // Hand-written: only this field.
      const UnitConfig d =
          overlay_unit_config(overlay(u, f, json_value(f, v)), UnitConfig{}, "test.json");
      EXPECT_EQ(f.get(d.specular), v) << u.field_name(f);
      EXPECT_EQ(d.specular.kind, u.kind);
    }
  }
}

TEST(SpecularUnits, JsonRefusesOutOfRangeNamingTheField) {
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      const std::string path = "specular." + u.field_name(f);
      std::vector<std::string> bad;
      if (f.is_enum()) {
        bad = {R"("no-such-value")", "3"};
      } else {
        for (int v : rejected_values(f)) bad.push_back(std::to_string(v));
        bad.push_back(R"("12")");
      }
      for (const std::string& value : bad) {
        const std::string msg = overlay_error(overlay(u, f, value));
        // The reader names the JSON path; validate() names "<unit>.<key>" (which it contains).
        EXPECT_NE(msg.find(u.field_name(f)), std::string::npos) << value << " -> '" << msg << "'";
        EXPECT_NE(msg.find("test.json"), std::string::npos) << msg;
      }
    }
  }
  // A rule across fields (the LUT's check): interpolation needs two entries.
  const std::string lut =
      overlay_error(R"({"specular": {"kind": "lut", "lut": {"addr_bits": 1, "interp_bits": 2}}})");
  EXPECT_NE(lut.find("lut.addr_bits must be >= 2 with interpolation"), std::string::npos) << lut;
  EXPECT_EQ(overlay_error(R"({"specular": {"kind": "lut", "lut": {"addr_bits": 1}}})"), "");
  // Unknown keys list the table's keys.
  const std::string msg = overlay_error(R"({"specular": {"wpow": {"m": 4}}})");
  EXPECT_NE(
      msg.find("specular.wpow.m: unknown field; expected one of max_m, base_bits, timing, fit"),
      std::string::npos)
      << msg;
}

TEST(SpecularUnits, EveryFieldHasACommandLineOptionThatSetsIt) {
  std::map<std::string, std::vector<std::string>> fields_of_option;
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      ASSERT_NE(*f.cli, '\0') << u.field_name(f) << " has no option";
      fields_of_option[f.cli].push_back(u.field_name(f));
      const int v = other_value(f, SpecularConfig{});
      const UnitConfig c = parse_cli({f.cli, f.text([&] {
                                        SpecularConfig s;
                                        f.set(s, v);
                                        return s;
                                      }())});
      EXPECT_EQ(f.get(c.specular), v) << f.cli;
      // Out of range: refused naming the option.
      const std::vector<std::string> bad =
          f.is_enum() ? std::vector<std::string>{"no-such-value"} : [&] {
            std::vector<std::string> b = {"x7"};
            for (int x : rejected_values(f)) b.push_back(std::to_string(x));
            return b;
          }();
      for (const std::string& value : bad) {
        const std::string msg = cli_error({f.cli, value});
        EXPECT_NE(msg.find(f.cli), std::string::npos)
            << f.cli << " " << value << " -> '" << msg << "'";
      }
    }
  }
  // A shared option (--fit) sets every field that names it; those fields agree on their values.
  EXPECT_EQ(fields_of_option.at("--fit").size(), 3u);
  const UnitConfig c = parse_cli({"--fit", "epicentre"});
  EXPECT_EQ(c.specular.lut.fit, FitObjective::kEpicentre);
  EXPECT_EQ(c.specular.schlick.fit, FitObjective::kEpicentre);
  EXPECT_EQ(c.specular.wpow.fit, FitObjective::kEpicentre);
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      for (const SpecularUnitDescriptor& v : specular_units()) {
        for (const SpecularField& g : v.fields) {
          if (std::string(f.cli) != g.cli) continue;
          EXPECT_EQ(f.expected(), g.expected()) << u.field_name(f) << " and " << v.field_name(g);
        }
      }
    }
  }
  // The options the README and the tests use by name.
  const UnitConfig d =
      parse_cli({"--lut-addr-bits", "12", "--wpow-m", "8", "--schlick-timing", "pipelined"});
  EXPECT_EQ(d.specular.lut.addr_bits, 12);
  EXPECT_EQ(d.specular.wpow.max_m, 8);
  EXPECT_EQ(d.specular.schlick.timing, UnitTiming::kPipelined);
}

TEST(SpecularUnits, HardwareFieldsReachTheirVerilogParameterOthersDoNot) {
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      UnitConfig c = on(u);
      const auto before = as_map(shade_unit_parameters(c));
      f.set(c.specular, other_value(f, c.specular));
      const auto after = as_map(shade_unit_parameters(c));
      if (*f.verilog) {
        ASSERT_EQ(after.count(f.verilog), 1u) << f.verilog;
        EXPECT_EQ(after.at(f.verilog), f.get(c.specular)) << f.verilog;
        EXPECT_NE(before.at(f.verilog), after.at(f.verilog)) << f.verilog;
      } else {
        EXPECT_EQ(before, after) << u.field_name(f) << " is host-only but changed the parameters";
      }
      // Another unit's fields never appear.
      for (const SpecularUnitDescriptor& v : specular_units()) {
        if (&v == &u) continue;
        for (const SpecularField& g : v.fields) {
          if (*g.verilog) {
            EXPECT_EQ(after.count(g.verilog), 0u) << g.verilog << " on " << u.name;
          }
        }
      }
    }
  }
}

// shade_unit's `parameter int NAME = VALUE` lines.
std::map<std::string, std::string> shade_unit_sv_parameters() {
  std::ifstream is(std::string(SHADESIM_SOURCE_DIR) + "/rtl/shade_unit.sv");
  EXPECT_TRUE(is) << "cannot read rtl/shade_unit.sv";
  std::map<std::string, std::string> m;
  const std::regex line(R"(^\s*parameter\s+int\s+(\w+)\s*=\s*([^,/\s]+))");
  for (std::string s; std::getline(is, s);) {
    std::smatch match;
    if (std::regex_search(s, match, line)) m[match[1]] = match[2];
  }
  return m;
}

TEST(SpecularUnits, VerilogNamesAndDefaultsAreShadeUnitsOwn) {
  const auto sv = shade_unit_sv_parameters();
  // Spot checks, written out from rtl/shade_unit.sv's parameter list.
  EXPECT_EQ(sv.at("LUT_ADDR_BITS"), "10");
  EXPECT_EQ(sv.at("SCHLICK_OPERAND_BITS"), "24");
  EXPECT_EQ(sv.at("WPOW_TIMING"), "0");
  const std::map<std::string, int64_t> rtl_defaults = {
      {"LUT_ADDR_BITS", 10},         {"LUT_ENTRY_BITS", 8},
      {"LUT_INTERP_BITS", 0},        {"LUT_INDEX", 0},
      {"SCHLICK_QUOTIENT_BITS", 16}, {"SCHLICK_OPERAND_BITS", 24},
      {"SCHLICK_TIMING", 1},         {"WPOW_MAX_M", 16},
      {"WPOW_BASE_BITS", 16},        {"WPOW_TIMING", 0}};
  std::set<std::string> in_table;
  for (const SpecularUnitDescriptor& u : specular_units()) {
    const auto p = as_map(shade_unit_parameters(on(u)));
    if (u.hardware) {
      EXPECT_EQ(p.at("SPECULAR_KIND"), u.verilog_kind);
    }
    for (const SpecularField& f : u.fields) {
      if (!*f.verilog) continue;
      in_table.insert(f.verilog);
      ASSERT_EQ(sv.count(f.verilog), 1u) << f.verilog << " is not a parameter of rtl/shade_unit.sv";
      // The model's default is the RTL's default, so an unset parameter means the same unit.
      EXPECT_EQ(std::to_string(p.at(f.verilog)), sv.at(f.verilog)) << f.verilog;
      EXPECT_EQ(p.at(f.verilog), rtl_defaults.at(f.verilog)) << f.verilog;
    }
  }
  // Every unit parameter of shade_unit has its row.
  for (const auto& [name, value] : sv) {
    if (std::regex_match(name, std::regex("(LUT|SCHLICK|WPOW)_\\w+"))) {
      EXPECT_EQ(in_table.count(name), 1u)
          << name << " of rtl/shade_unit.sv has no row in the table";
    }
  }
  EXPECT_EQ(in_table.size(), rtl_defaults.size());
}

TEST(SpecularUnits, SlotTimingIsShadePkgsSpecLatencyAndInterval) {
  // rtl/shade_pkg.sv: latency lut 2 (3 with interpolation), schlick Q, wpow clog2(m) + 1;
  // interval = latency for an iterative unit, else 1.
  SpecularConfig s;
  EXPECT_EQ(SlotTiming::of(s).latency, 0);
  s.kind = SpecularUnitKind::kLut;
  s.lut.interp_bits = 3;
  EXPECT_EQ(SlotTiming::of(s).latency, 3);
  EXPECT_EQ(SlotTiming::of(s).interval, 1);
  s.kind = SpecularUnitKind::kSchlick;
  s.schlick.quotient_bits = 11;
  EXPECT_EQ(SlotTiming::of(s).latency, 11);
  EXPECT_EQ(SlotTiming::of(s).interval, 11);
  s.kind = SpecularUnitKind::kWpow;
  s.wpow.max_m = 8;
  s.wpow.timing = UnitTiming::kIterative;
  EXPECT_EQ(SlotTiming::of(s).latency, 4);
  EXPECT_EQ(SlotTiming::of(s).interval, 4);
  // spec-error's cost columns carry the same timing.
  for (const SpecularUnitDescriptor& u : specular_units()) {
    SpecularConfig c;
    c.kind = u.kind;
    EXPECT_EQ(specular_cost(c).latency, SlotTiming::of(c).latency) << u.name;
    EXPECT_EQ(specular_cost(c).cycles_per_pixel, SlotTiming::of(c).interval) << u.name;
  }
}

}  // namespace
}  // namespace shadesim
