#include "model/specular_units.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "model/exponent_lut.h"
#include "model/schlick_divider.h"
#include "model/wpow_unit.h"

namespace shadesim {
namespace {

// An enum field's code is its value in its SPEC_PARAMS slot (the decode comments at the top of
// rtl/exponent_lut.sv, schlick_divider.sv, wpow_unit.sv).
static_assert(static_cast<int>(LutIndex::kTruncate) == 0 &&
                  static_cast<int>(LutIndex::kNearest) == 1,
              "exponent_lut INDEX: 0 truncate, 1 nearest");
static_assert(static_cast<int>(UnitTiming::kPipelined) == 0 &&
                  static_cast<int>(UnitTiming::kIterative) == 1,
              "schlick_divider / wpow_unit TIMING: 0 pipelined, 1 iterative");

// Accessors of SpecularConfig::*Unit.*Member as an int.
template <auto Unit, auto Member>
int get(const SpecularConfig& c) {
  return static_cast<int>((c.*Unit).*Member);
}
template <auto Unit, auto Member>
void set(SpecularConfig& c, int v) {
  using T = std::remove_reference_t<decltype((c.*Unit).*Member)>;
  (c.*Unit).*Member = static_cast<T>(v);
}
template <typename E>
std::string name_of(int code) {
  return to_string(static_cast<E>(code));
}

constexpr const char* kFitHelp = "per-exponent fit of zeta / n' / k (W_m, Schlick, shared LUT)";
constexpr int kFitHi = static_cast<int>(FitObjective::kAbsolute);
constexpr auto kLut = &SpecularConfig::lut;
constexpr auto kSchlick = &SpecularConfig::schlick;
constexpr auto kWpow = &SpecularConfig::wpow;
using L = LutConfig;
using S = SchlickConfig;
using W = WpowConfig;

std::string timing_tag(UnitTiming t) { return t == UnitTiming::kIterative ? " iter" : " pipe"; }
std::string fit_tag(FitObjective f) {
  return f == FitObjective::kNone ? "" : " fit=" + to_string(f);
}

// A row with no specular hardware (ideal: exact pow in the model, its RTL slot outputs 0; none:
// no specular term at all): no fields, latency 0, one pixel per cycle, no cost, no label, no size.
SpecularUnitDescriptor unit_without_hardware(SpecularUnitKind kind, const char* name,
                                             int verilog_kind, int series_per_light) {
  return {kind,
          name,
          verilog_kind,
          false,
          series_per_light,
          {},
          [](const SpecularConfig&) { return 0; },
          [](const SpecularConfig&) { return 1; },
          [](const SpecularConfig&) { return SpecularCost{}; },
          [](const SpecularConfig&) { return std::string(); },
          [](const SpecularConfig&, int) { return 0.0; }};
}

SpecularUnitDescriptor lut_unit() {
  return {SpecularUnitKind::kLut,
          "lut",
          1,
          true,
          1,
          {
              // At most 16: a TABLE command addresses 2^16 entries (its 16-bit base and count,
              // model/command_word.h), and exponent_lut.sv refuses more (CFG_ADDR_W).
              {"addr_bits", "--lut-addr-bits", "LUT: address bits A (2^A entries)", "ADDR_BITS", 0,
               1, 16, false, nullptr, get<kLut, &L::addr_bits>, set<kLut, &L::addr_bits>, 4,
               [](int v) { return std::min(v + 2, 16); }},
              {"entry_bits", "--lut-entry-bits", "LUT: entry bits B", "ENTRY_BITS", 1, 1, 32, false,
               nullptr, get<kLut, &L::entry_bits>, set<kLut, &L::entry_bits>, 4,
               [](int v) { return std::min(v + 4, 32); }},
              {"interp_bits", "--lut-interp-bits", "LUT: interpolation fraction bits (0 = off)",
               "INTERP_BITS", 2, 0, 16, false, nullptr, get<kLut, &L::interp_bits>,
               set<kLut, &L::interp_bits>, 0, [](int v) { return std::max(v, 4); }},
              {"index", "--lut-index", "LUT: address rounding", "INDEX", 3, 0, 1, false,
               name_of<LutIndex>, get<kLut, &L::index>, set<kLut, &L::index>},
              {"addressing", "--lut-addressing",
               "LUT: a table per exponent (reloaded per material) or one shared", "", -1, 0, 1,
               false, name_of<LutAddressing>, get<kLut, &L::addressing>, set<kLut, &L::addressing>},
              {"shared_range_log2", "--lut-shared-range-log2",
               "LUT, shared table: log2 of the range U of u = k (1 - t) it spans", "", -1, 0, 6,
               false, nullptr, get<kLut, &L::shared_range_log2>, set<kLut, &L::shared_range_log2>},
              {"fit", "--fit", kFitHelp, "", -1, 0, kFitHi, false, name_of<FitObjective>,
               get<kLut, &L::fit>, set<kLut, &L::fit>},
          },
          [](const SpecularConfig& c) { return ExponentLut::latency(c.lut); },
          [](const SpecularConfig& c) { return ExponentLut::cycles_per_pixel(c.lut); },
          [](const SpecularConfig& c) {
            SpecularCost k;
            const LutConfig& l = c.lut;
            k.table_bits = ExponentLut::table_bits(l);
            k.multipliers = ExponentLut::multipliers(l);
            k.reload_cycles = ExponentLut::reload_cycles(l);
            // The interpolator: an (F+1) x (B+1) multiplier plus a (B+F)-bit adder.
            k.area =
                static_cast<double>(k.table_bits) +
                (l.interp_bits > 0 ? kFullAdderArea * ((l.interp_bits + 1) * (l.entry_bits + 1) +
                                                       l.entry_bits + l.interp_bits)
                                   : 0.0);
            return k;
          },
          [](const SpecularConfig& c) {
            const LutConfig& l = c.lut;
            std::ostringstream os;
            os << (l.addressing == LutAddressing::kShared ? " shared" : " per-n")
               << " A=" << l.addr_bits << " B=" << l.entry_bits
               << (l.index == LutIndex::kTruncate ? " trn" : " near");
            if (l.interp_bits > 0) os << " F=" << l.interp_bits;
            if (l.addressing == LutAddressing::kShared)
              os << " U=2^" << l.shared_range_log2 << fit_tag(l.fit);
            return os.str();
          },
          [](const SpecularConfig& c, int series_wl) {
            // The table's bits, plus the address and interpolation datapath.
            const LutConfig& l = c.lut;
            return std::ldexp(static_cast<double>(l.entry_bits), l.addr_bits) +
                   static_cast<double>(l.entry_bits * (l.interp_bits + 1)) * series_wl;
          },
          [](const SpecularConfig& c) {
            if (c.lut.interp_bits > 0 && c.lut.addr_bits < 2)
              throw std::invalid_argument(
                  "lut.addr_bits must be >= 2 with interpolation (two entries per interval)");
          }};
}

SpecularUnitDescriptor schlick_unit() {
  return {
      SpecularUnitKind::kSchlick,
      "schlick",
      2,
      true,
      2,  // numerator and denominator series
      {
          {"quotient_bits", "--schlick-quotient-bits",
           "Schlick: quotient bits Q (divider iterations)", "QUOTIENT_BITS", 0, 1, 32, false,
           nullptr, get<kSchlick, &S::quotient_bits>, set<kSchlick, &S::quotient_bits>, 4,
           [](int v) { return std::min(v + 2, 32); }},
          {"operand_bits", "--schlick-operand-bits",
           "Schlick: fraction bits D of the divider's operands", "OPERAND_BITS", 1, 2, 48, false,
           nullptr, get<kSchlick, &S::operand_bits>, set<kSchlick, &S::operand_bits>, 8,
           [](int v) { return std::min(v + 4, 48); }},
          {"timing", "--schlick-timing", "Schlick: iterative = Q cycles/pixel, pipelined = 1",
           "TIMING", 2, 0, 1, false, name_of<UnitTiming>, get<kSchlick, &S::timing>,
           set<kSchlick, &S::timing>},
          {"fit", "--fit", kFitHelp, "", -1, 0, kFitHi, false, name_of<FitObjective>,
           get<kSchlick, &S::fit>, set<kSchlick, &S::fit>},
      },
      [](const SpecularConfig& c) { return SchlickDivider::latency(c.schlick); },
      [](const SpecularConfig& c) { return SchlickDivider::cycles_per_pixel(c.schlick); },
      [](const SpecularConfig& c) {
        SpecularCost k;
        k.divider_iterations = SchlickDivider::iterations(c.schlick);
        // Each subtract/compare stage is D + 3 bits wide.
        k.area = kFullAdderArea * SchlickDivider::subtractor_stages(c.schlick) *
                 (c.schlick.operand_bits + 3);
        return k;
      },
      [](const SpecularConfig& c) {
        std::ostringstream os;
        os << " Q=" << c.schlick.quotient_bits << " D=" << c.schlick.operand_bits
           << timing_tag(c.schlick.timing) << fit_tag(c.schlick.fit);
        return os.str();
      },
      [](const SpecularConfig& c, int) {
        // Q x D divider bits, once (iterative) or per stage (pipelined).
        const SchlickConfig& d = c.schlick;
        return static_cast<double>(d.quotient_bits * d.operand_bits) *
               (d.timing == UnitTiming::kIterative ? 1.0 : static_cast<double>(d.quotient_bits));
      }};
}

SpecularUnitDescriptor wpow_unit() {
  SpecularUnitDescriptor d = {
      SpecularUnitKind::kWpow,
      "wpow",
      3,
      true,
      1,
      {
          {"max_m", "--wpow-m", "W_m: m (4, 8 or 16)", "MAX_M", 0, 1, 32, true, nullptr,
           get<kWpow, &W::max_m>, set<kWpow, &W::max_m>},
          {"base_bits", "--wpow-bits", "W_m: fraction bits B of the base and squares", "BASE_BITS",
           1, 2, 30, false, nullptr, get<kWpow, &W::base_bits>, set<kWpow, &W::base_bits>, 6,
           [](int v) { return std::min(v + 4, 30); }},
          {"timing", "--wpow-timing", "W_m: pipelined = 1 cycle/pixel, iterative = log2(m) + 1",
           "TIMING", 2, 0, 1, false, name_of<UnitTiming>, get<kWpow, &W::timing>,
           set<kWpow, &W::timing>},
          {"square_stages", "--wpow-square-stages",
           "W_m: registers per squaring, 1 or 2 (pipelined: a shorter clock path)", "SQUARE_STAGES",
           3, 1, 2, false, nullptr, get<kWpow, &W::square_stages>, set<kWpow, &W::square_stages>},
          {"fit", "--fit", kFitHelp, "", -1, 0, kFitHi, false, name_of<FitObjective>,
           get<kWpow, &W::fit>, set<kWpow, &W::fit>},
      },
      [](const SpecularConfig& c) { return WpowUnit::latency(c.wpow); },
      [](const SpecularConfig& c) { return WpowUnit::cycles_per_pixel(c.wpow); },
      [](const SpecularConfig& c) {
        SpecularCost k;
        k.multipliers = WpowUnit::multipliers(c.wpow);
        const double b = c.wpow.base_bits + 1;
        k.area =
            kFullAdderArea * k.multipliers * b * b / 2.0;  // a squarer is about half a multiplier
        return k;
      },
      [](const SpecularConfig& c) {
        std::ostringstream os;
        os << " m=" << c.wpow.max_m << " B=" << c.wpow.base_bits << timing_tag(c.wpow.timing)
           << (c.wpow.square_stages > 1 ? " sq2" : "") << fit_tag(c.wpow.fit);
        return os.str();
      },
      [](const SpecularConfig& c, int series_wl) {
        // B x B squarers, one (iterative) or log2(m) (pipelined), plus the base stage.
        const double b = c.wpow.base_bits;
        const double k = WpowUnit::stages(c.wpow);
        return b * b * (c.wpow.timing == UnitTiming::kIterative ? 1.0 : k) + b * series_wl;
      }};
  d.check = [](const SpecularConfig& c) {
    if (c.wpow.square_stages != 1 && c.wpow.timing != UnitTiming::kPipelined)
      throw std::invalid_argument("wpow.square_stages " + std::to_string(c.wpow.square_stages) +
                                  " needs wpow.timing pipelined (an iterative unit squares in "
                                  "one cycle)");
  };
  return d;
}

std::vector<SpecularUnitDescriptor> make_table() {
  std::vector<SpecularUnitDescriptor> t;
  t.push_back(unit_without_hardware(SpecularUnitKind::kIdeal, "ideal", 0, 1));
  t.push_back(lut_unit());
  t.push_back(schlick_unit());
  t.push_back(wpow_unit());
  // No specular term: shade_unit instantiates no specular_unit and no specular series (nor their
  // span setup and engines), and pixel_combine adds nothing; MATERIAL carries no unit parameters.
  t.push_back(unit_without_hardware(SpecularUnitKind::kNone, "none", 4, 0));
  return t;
}

}  // namespace

bool SpecularField::in_range(int v) const {
  return v >= lo && v <= hi && (!power_of_two || (v > 0 && (v & (v - 1)) == 0));
}

std::string SpecularField::expected() const {
  if (is_enum()) {
    std::string names;
    for (int v = lo; v <= hi; ++v) names += (names.empty() ? "" : ", ") + value_name(v);
    return "one of " + names;
  }
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  return power_of_two ? "a power of two " + range : range;
}

std::string SpecularField::text(const SpecularConfig& c) const {
  return is_enum() ? value_name(get(c)) : std::to_string(get(c));
}

int SpecularField::parse(const std::string& text, const std::string& what) const {
  if (is_enum()) {
    for (int v = lo; v <= hi; ++v) {
      if (text == value_name(v)) return v;
    }
    throw std::invalid_argument(what + ": unknown value '" + text + "'; expected " + expected());
  }
  size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || v < -1000000 || v > 1000000) {
    throw std::invalid_argument(what + ": expected an integer (" + expected() + "), got '" + text +
                                "'");
  }
  return static_cast<int>(v);
}

const std::vector<SpecularUnitDescriptor>& specular_units() {
  static const std::vector<SpecularUnitDescriptor> table = make_table();
  return table;
}

const SpecularUnitDescriptor& specular_unit(SpecularUnitKind kind) {
  for (const auto& u : specular_units()) {
    if (u.kind == kind) return u;
  }
  throw std::logic_error("specular_unit: SpecularUnitKind " +
                         std::to_string(static_cast<int>(kind)) +
                         " has no row in model/specular_units.cpp");
}

const SpecularUnitDescriptor* find_specular_unit(const std::string& name) {
  for (const auto& u : specular_units()) {
    if (name == u.name) return &u;
  }
  return nullptr;
}

std::string specular_unit_names(bool hardware_only) {
  std::string names;
  for (const auto& u : specular_units()) {
    if (hardware_only && !u.hardware) continue;
    names += (names.empty() ? "" : ", ") + std::string(u.name);
  }
  return names;
}

SpecularConfig specular_config_of_parameters(const std::map<std::string, int64_t>& params) {
  const auto kind = params.find("SPECULAR_KIND");
  if (kind == params.end()) throw std::invalid_argument("parameters: SPECULAR_KIND missing");
  for (const SpecularUnitDescriptor& u : specular_units()) {
    if (u.verilog_kind != kind->second) continue;
    SpecularConfig s;
    s.kind = u.kind;
    for (const SpecularField& f : u.fields) {
      if (f.slot < 0) continue;
      if (const auto it = params.find("SPEC_PARAMS[" + std::to_string(f.slot) + "]");
          it != params.end())
        f.set(s, static_cast<int>(it->second));
    }
    return s;
  }
  throw std::invalid_argument("parameters: SPECULAR_KIND " + std::to_string(kind->second) +
                              " is no unit of model/specular_units.cpp");
}

SpecularCost specular_cost(const SpecularConfig& config) {
  const SpecularUnitDescriptor& u = specular_unit(config.kind);
  SpecularCost k = u.cost(config);
  k.latency = u.latency(config);
  k.cycles_per_pixel = u.interval(config);
  return k;
}

}  // namespace shadesim
