// The specular unit table (model/specular_units.h) against the code that walks it: every field
// of every unit round-trips through the UnitConfig JSON, has a command-line option that sets
// it, reaches its slot of SPEC_PARAMS, and is refused out of range with an error naming it. The
// slots, names and defaults are checked against each unit module's decode (rtl/exponent_lut.sv,
// ...), read from the file, and a few slot timings against rtl/shade_pkg.sv's spec_latency
// written out by hand.
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
#include "model/specular_unit.h"
#include "model/unit_config_file.h"
#include "sim/cli/width_options.h"

namespace shadesim {
namespace {

std::map<std::string, int64_t> as_map(const std::vector<VerilogParameter>& params) {
  return parameter_map(params);
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
  std::set<std::string> names;
  std::set<int> codes;
  for (const SpecularUnitKind k :
       {SpecularUnitKind::kIdeal, SpecularUnitKind::kLut, SpecularUnitKind::kSchlick,
        SpecularUnitKind::kWpow, SpecularUnitKind::kNone}) {
    const SpecularUnitDescriptor& u = specular_unit(k);
    EXPECT_EQ(u.kind, k);
    EXPECT_TRUE(names.insert(u.name).second) << u.name;
    EXPECT_TRUE(codes.insert(u.verilog_kind).second) << u.name;
    EXPECT_EQ(find_specular_unit(u.name), &u);
    std::set<std::string> keys, verilog;
    std::set<int> slots;
    for (const SpecularField& f : u.fields) {
      EXPECT_TRUE(keys.insert(f.key).second) << u.field_name(f) << " twice";
      if (*f.verilog) {
        EXPECT_TRUE(verilog.insert(f.verilog).second) << f.verilog << " twice";
        EXPECT_TRUE(slots.insert(f.slot).second) << u.field_name(f) << ": slot twice";
        EXPECT_GE(f.slot, 0) << u.field_name(f);
        EXPECT_LT(f.slot, kSpecSlots) << u.field_name(f);
      } else {
        EXPECT_EQ(f.slot, -1) << u.field_name(f);
      }
      EXPECT_LE(f.lo, f.hi) << u.field_name(f);
      EXPECT_TRUE(f.in_range(f.get(SpecularConfig{})))
          << u.field_name(f) << "'s default is out of range";
    }
  }
  EXPECT_EQ(specular_units().size(), 5u);
  EXPECT_EQ(find_specular_unit("nope"), nullptr);
  EXPECT_EQ(specular_unit_names(), "ideal, lut, schlick, wpow, none");
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
  EXPECT_NE(msg.find("specular.wpow.m: unknown field; expected one of max_m, base_bits, timing, "
                     "square_stages, fit"),
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

TEST(SpecularUnits, HardwareFieldsReachTheirSlotOthersDoNot) {
  for (const SpecularUnitDescriptor& u : specular_units()) {
    for (const SpecularField& f : u.fields) {
      UnitConfig c = on(u);
      const auto before = as_map(shade_unit_parameters(c));
      f.set(c.specular, other_value(f, c.specular));
      const auto after = as_map(shade_unit_parameters(c));
      if (f.slot >= 0) {
        const std::string slot = "SPEC_PARAMS[" + std::to_string(f.slot) + "]";
        ASSERT_EQ(after.count(slot), 1u) << u.field_name(f);
        EXPECT_EQ(after.at(slot), f.get(c.specular)) << u.field_name(f);
        EXPECT_NE(before.at(slot), after.at(slot)) << u.field_name(f);
        // Only that slot changed.
        auto rest = after;
        rest[slot] = before.at(slot);
        EXPECT_EQ(rest, before) << u.field_name(f) << " changed another parameter";
      } else {
        EXPECT_EQ(before, after) << u.field_name(f) << " is host-only but changed the parameters";
      }
    }
    // Slots no field of the unit uses stay 0.
    const auto p = as_map(shade_unit_parameters(on(u)));
    for (int k = 0; u.hardware && k < kSpecSlots; ++k) {
      const bool used = std::any_of(u.fields.begin(), u.fields.end(),
                                    [&](const SpecularField& f) { return f.slot == k; });
      if (!used) EXPECT_EQ(p.at("SPEC_PARAMS[" + std::to_string(k) + "]"), 0) << u.name << k;
    }
  }
}

std::string read_rtl(const std::string& file) {
  std::ifstream is(std::string(SHADESIM_SOURCE_DIR) + "/rtl/" + file);
  EXPECT_TRUE(is) << "cannot read rtl/" << file;
  std::ostringstream os;
  os << is.rdbuf();
  return os.str();
}

// Each hardware unit's module, which decodes its own slots of SPEC_PARAMS.
std::string unit_module_file(SpecularUnitKind kind) {
  switch (kind) {
    case SpecularUnitKind::kLut:
      return "exponent_lut.sv";
    case SpecularUnitKind::kSchlick:
      return "schlick_divider.sv";
    case SpecularUnitKind::kWpow:
      return "wpow_unit.sv";
    default:
      return "";
  }
}

TEST(SpecularUnits, EachUnitModuleDecodesItsRowsSlotsWithTheModelsDefaults) {
  // shade_pkg's packing is rtl_parameters.h's.
  const std::string pkg = read_rtl("shade_pkg.sv");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(pkg, m, std::regex(R"(localparam int SpecSlots\s*=\s*(\d+);)")));
  EXPECT_EQ(std::stoi(m[1]), kSpecSlots);
  ASSERT_TRUE(std::regex_search(pkg, m, std::regex(R"(localparam int SpecSlotW\s*=\s*(\d+);)")));
  EXPECT_EQ(std::stoi(m[1]), kSpecSlotBits);
  // shade_unit carries no unit field by name: only the packed parameter.
  const std::string top = read_rtl("shade_unit.sv");
  EXPECT_FALSE(std::regex_search(top, std::regex(R"(parameter\s+int\s+(LUT|SCHLICK|WPOW)_)")));
  EXPECT_NE(top.find("SPEC_PARAMS"), std::string::npos);

  for (const SpecularUnitDescriptor& u : specular_units()) {
    if (!u.hardware) continue;
    const std::string sv = read_rtl(unit_module_file(u.kind));
    // "localparam int NAME = shade_pkg::spec_slot(SPEC_PARAMS, K);"
    std::map<std::string, int> decoded;
    const std::regex line(
        R"(localparam int (\w+)\s*=\s*shade_pkg::spec_slot\(SPEC_PARAMS, (\d+)\))");
    for (auto it = std::sregex_iterator(sv.begin(), sv.end(), line); it != std::sregex_iterator();
         ++it)
      decoded[(*it)[1]] = std::stoi((*it)[2]);
    // The module's SPEC_PARAMS default "{{(shade_pkg::SpecSlots - N){32'd0}}, 32'dV, ..., 32'dV0}".
    ASSERT_TRUE(std::regex_search(
        sv, m,
        std::regex(R"(SPEC_PARAMS =\s*\{\{\(shade_pkg::SpecSlots - (\d+)\)\{32'd0\}\},([^}]*)\})")))
        << u.name;
    std::vector<int64_t> defaults;
    const std::string list = m[2];
    const std::regex value(R"(32'd(\d+))");
    for (auto it = std::sregex_iterator(list.begin(), list.end(), value);
         it != std::sregex_iterator(); ++it)
      defaults.insert(defaults.begin(), std::stoll((*it)[1]));  // written high slot first
    EXPECT_EQ(defaults.size(), static_cast<size_t>(std::stoi(m[1]))) << u.name;

    const SpecularConfig model_default = on(u).specular;
    size_t hardware_fields = 0;
    for (const SpecularField& f : u.fields) {
      if (f.slot < 0) {
        EXPECT_STREQ(f.verilog, "") << u.field_name(f);
        continue;
      }
      ++hardware_fields;
      ASSERT_EQ(decoded.count(f.verilog), 1u)
          << u.field_name(f) << ": " << unit_module_file(u.kind) << " decodes no " << f.verilog;
      EXPECT_EQ(decoded.at(f.verilog), f.slot) << u.field_name(f);
      // The RTL's default is the model's, so the standalone module is the default unit.
      ASSERT_LT(static_cast<size_t>(f.slot), defaults.size()) << u.field_name(f);
      EXPECT_EQ(defaults[static_cast<size_t>(f.slot)], f.get(model_default)) << u.field_name(f);
    }
    // Every slot the module decodes has its row.
    EXPECT_EQ(decoded.size(), hardware_fields) << u.name;
  }
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
  // none: no slot at all, nothing between the engines and pixel_combine.
  s.kind = SpecularUnitKind::kNone;
  EXPECT_EQ(SlotTiming::of(s).latency, 0);
  EXPECT_EQ(SlotTiming::of(s).interval, 1);
  // spec-error's cost columns carry the same timing.
  for (const SpecularUnitDescriptor& u : specular_units()) {
    SpecularConfig c;
    c.kind = u.kind;
    EXPECT_EQ(specular_cost(c).latency, SlotTiming::of(c).latency) << u.name;
    EXPECT_EQ(specular_cost(c).cycles_per_pixel, SlotTiming::of(c).interval) << u.name;
  }
}

TEST(SpecularUnits, NoneHasNoSeriesNoParametersAndShadesNoSpecularTerm) {
  const SpecularUnitDescriptor& none = specular_unit(SpecularUnitKind::kNone);
  EXPECT_STREQ(none.name, "none");
  EXPECT_EQ(parse_specular_unit("none", "test"), SpecularUnitKind::kNone);
  EXPECT_EQ(none.series_per_light, 0);
  EXPECT_TRUE(none.fields.empty());
  EXPECT_FALSE(none.hardware);
  // shade_unit's SPECULAR_KIND 4 (shade_pkg SpecNone), no output rounding and no SPEC_PARAMS.
  const std::string pkg = read_rtl("shade_pkg.sv");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(pkg, m, std::regex(R"(localparam int SpecNone\s*=\s*(\d+);)")));
  EXPECT_EQ(std::stoi(m[1]), none.verilog_kind);
  UnitConfig c;
  c.channels = 3;
  c.lights = 2;
  c.specular.kind = SpecularUnitKind::kNone;
  EXPECT_EQ(c.specular_series(), 0);
  EXPECT_EQ(c.series_per_triangle(), c.diffuse_series());
  const auto p = as_map(shade_unit_parameters(c));
  EXPECT_EQ(p.at("SPECULAR_KIND"), 4);
  EXPECT_EQ(p.count("SPECULAR_OUT_QUANT"), 0u);
  EXPECT_EQ(p.count("SPEC_PARAMS[0]"), 0u);
  EXPECT_EQ(specular_config_of_parameters(p).kind, SpecularUnitKind::kNone);
  // The unit gives 0 whatever its (absent) series hold, and a MATERIAL carries no parameters.
  SpecularUnit unit(c);
  MaterialCmd mat;
  mat.exponent = int64_t{30} << kExponentFracBits;
  unit.load_material(mat);
  const int64_t series[2] = {c.series.from_double(1.0), c.series.from_double(1.0)};
  EXPECT_EQ(unit.evaluate(series), 0);
}

}  // namespace
}  // namespace shadesim
