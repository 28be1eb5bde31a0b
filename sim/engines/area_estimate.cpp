// estimate_area (sim/engines/area_report.h): a unit's area scaled module by module from a measured
// anchor, for the points of a width sweep that are never synthesised.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "model/specular_units.h"
#include "sim/eda/yosys/area_generic.h"
#include "sim/engines/area_report.h"

namespace shadesim {
namespace {

using ParamMap = std::map<std::string, int64_t>;

// SPEC_PARAMS as one entry per slot, so a differing unit field counts as one parameter.
ParamMap param_map(const std::vector<VerilogParameter>& ps) { return parameter_map(ps); }

int64_t get(const ParamMap& p, const char* name) {
  const auto it = p.find(name);
  if (it == p.end())
    throw std::runtime_error(std::string("area estimate: parameter ") + name + " missing");
  return it->second;
}

// LANES, 1 for a measurement made before the parameter existed.
int64_t lanes_of(const ParamMap& p) {
  const auto it = p.find("LANES");
  return it == p.end() ? 1 : it->second;
}

// Host span setup (SPAN_SETUP 1): no span setup, coefficient banks or span queue; a start bank.
bool host_setup_of(const ParamMap& p) {
  const auto it = p.find("SPAN_SETUP");
  return it != p.end() && it->second == 1;
}

// OFS_BITS, 17 (screen-sized) when the unit does not set it.
int64_t offset_bits_of(const ParamMap& p) {
  const auto it = p.find("OFS_BITS");
  return it == p.end() ? UnitConfig::kMaxOffsetBits : it->second;
}

// Instances of each module (shade_unit.sv: NSer series, one slot per light, one combine; with
// LANES > 1 an engine per series, a slot per light and a combine per lane, one span setup).
int64_t instances_of(const std::string& module, const ParamMap& p) {
  const int64_t l = get(p, "LIGHTS"), diffuse = generic_flow::diffuse_series_of(p);
  const int64_t per_light = specular_config_of_parameters(p).series_per_light();
  const int64_t lanes = lanes_of(p);
  const bool host = host_setup_of(p);
  if (module == "span_setup") return host ? 0 : diffuse + l * per_light;
  if (module == "coef_bank" || module == "span_queue" || module == "setup_ctrl")
    return host ? 0 : 1;
  if (module == "start_bank") return host ? 1 : 0;
  if (module == "series_engine") return (diffuse + l * per_light) * lanes;
  if (module == "specular_unit") return per_light == 0 ? 0 : l * lanes;  // none: no slot
  if (module == "pixel_combine") return lanes;
  return 1;  // shade_unit glue
}

// Structural size of one instance: what its cells grow with (the RTL's widths, see area.h).
double size_of(const std::string& module, const ParamMap& p) {
  const double c = static_cast<double>(get(p, "COEF_WL")),
               ci = static_cast<double>(get(p, "COEF_IWL"));
  const double s = static_cast<double>(get(p, "SERIES_WL")),
               si = static_cast<double>(get(p, "SERIES_IWL"));
  const double ch = static_cast<double>(get(p, "CHANNELS")),
               l = static_cast<double>(get(p, "LIGHTS"));
  const double so = static_cast<double>(get(p, "SPECULAR_OUT_WL")),
               sc = static_cast<double>(get(p, "SPEC_COLOUR_WL"));
  if (module == "span_setup") {
    // Horner form (rtl/span_setup.sv): four coefficient x offset products (offsets of
    // OFS_BITS o) in stage 1 and two bracket x offset products ((c + o) x o) in stage 2; a
    // c x k product has c k partial-product bits, and with a wrapping series only the low w
    // bits (up to the series' top) reach the output, at most w(w+1)/2 of them. Plus the
    // registers: five brackets and two offsets, three sums, three outputs.
    const double o = static_cast<double>(offset_bits_of(p));
    const double sum_w = c + 2 * o + 3;
    const double drop = (c - ci) - (s - si);
    const double w = get(p, "SERIES_OVERFLOW") == 1 ? std::min(sum_w, drop + s + 1) : sum_w;
    const auto product = [w](double a, double b) { return std::min(a * b, w * (w + 1) / 2); };
    return 4 * product(c, o) + 2 * product(c + o, o) + 8 * w + 2 * o + 3 * s;
  }
  if (module == "series_engine") return s;
  // The start bank: v, d, d2 of every series (and the payload steering per bit) per entry.
  if (module == "start_bank") {
    const auto depth = p.find("START_DEPTH");
    const double entries = depth == p.end() ? UnitConfig::kStartDepth : depth->second;
    return 3 * static_cast<double>(instances_of("series_engine", p)) * s * entries;
  }
  if (module == "pixel_combine") {
    // With the diffuse multiply, a (series integer + colour fraction bits) x colour product per
    // light and channel too (rtl/pixel_combine.sv truncates N.L to the colour's fraction).
    const bool multiply = generic_flow::diffuse_series_of(p) != static_cast<int64_t>(ch * l);
    const double nl =
        si - 1 + std::min(s - si, sc - static_cast<double>(get(p, "SPEC_COLOUR_IWL")));
    return ch * (l * so * sc + (multiply ? l * nl * sc : 0) + (l + 1) * (s + 4));
  }
  if (module == "specular_unit") {
    // The unit's own size (model/specular_units.cpp), from its parameters.
    const SpecularConfig unit = specular_config_of_parameters(p);
    return specular_unit(unit.kind).slot_size(unit, static_cast<int>(s));
  }
  // shade_unit glue: coefficient, ambient and specular-colour registers, the metadata line,
  // decoder and span pipeline (a fixed part).
  const int64_t series_per_lane = instances_of("series_engine", p) / lanes_of(p);  // exact
  const double nser = static_cast<double>(series_per_lane);
  const double coef_regs = host_setup_of(p) ? 0 : 6 * nser * c;  // host: no coefficients
  const double xy = static_cast<double>(get(p, "XY_BITS"));
  // Lanes add each lane's fan-out (three constant-multiplier adders per series, ~6 adder bits
  // per series bit) and widen the metadata line and the pix register.
  const double extra_lanes = static_cast<double>(lanes_of(p) - 1);
  const double diffuse_bits =
      static_cast<double>(generic_flow::diffuse_series_of(p)) * s;  // metadata line
  return coef_regs + ch * s + ch * l * sc + 2 * (2 * xy + diffuse_bits) + 400 +
         extra_lanes * (6 * nser * s + 2 * diffuse_bits);
}

}  // namespace

std::string AreaEstimate::label() const {
  return "estimate (scaled from Yosys run " + anchor_key + ", " +
         std::to_string(differing_parameters) + " parameter(s) differ)";
}

AreaEstimate estimate_area(const UnitConfig& unit, const std::vector<AreaReport>& anchors) {
  const ParamMap target = param_map(shade_unit_parameters(unit));
  const AreaReport* best = nullptr;
  int best_diff = 0;
  for (const auto& a : anchors) {
    // Only complete measurements: a breakdown, and no series lost by Yosys (check_series).
    if (a.modules.empty() || a.cells == 0 || a.breakdown_cells == 0 || !a.warnings.empty())
      continue;
    const ParamMap ap = param_map(a.parameters);
    if (get(ap, "SPECULAR_KIND") != get(target, "SPECULAR_KIND")) continue;
    // A host-setup anchor has no span setup, coefficient bank or span queue to scale: it is no
    // anchor for a unit-setup target.
    if (host_setup_of(ap) && !host_setup_of(target)) continue;
    // The other span setup site has other modules: only when no anchor of this one is there.
    constexpr int kOtherSite = 1000;
    int diff = host_setup_of(ap) != host_setup_of(target) ? kOtherSite : 0;
    for (const auto& [name, value] : target) {
      const auto it = ap.find(name);
      if (it == ap.end() || it->second != value) ++diff;
    }
    if (!best || diff < best_diff) {
      best = &a;
      best_diff = diff;
    }
  }
  if (!best) {
    throw std::runtime_error(
        "area estimate: no measured anchor with this specular unit (" +
        std::string(to_string(unit.specular.kind)) +
        ") and a per-module breakdown; run `shadesim area --config` on one first");
  }
  const ParamMap ap = param_map(best->parameters);
  double kept = 0;
  for (const auto& m : best->modules) {
    const double anchor_size = size_of(m.module, ap);
    const double ratio = anchor_size > 0 ? size_of(m.module, target) / anchor_size : 0.0;
    kept += static_cast<double>(m.cells_each) * ratio *
            static_cast<double>(instances_of(m.module, target));
  }
  // A host-setup target from a unit-setup anchor: the start bank the anchor lacks, at the
  // anchor's series engine cells per register bit (an engine is three registers and adders).
  if (host_setup_of(target) && !host_setup_of(ap)) {
    for (const auto& m : best->modules) {
      if (m.module != "series_engine" || size_of(m.module, ap) <= 0) continue;
      kept += static_cast<double>(m.cells_each) / (3 * size_of(m.module, ap)) *
              size_of("start_bank", target);
    }
  }
  const double flat =
      kept * static_cast<double>(best->cells) / static_cast<double>(best->breakdown_cells);
  AreaEstimate e;
  e.cells = static_cast<int64_t>(std::llround(flat));
  e.lut4 = static_cast<int64_t>(std::llround(flat * static_cast<double>(best->ice40.lut4) /
                                             static_cast<double>(best->cells)));
  e.gate_equivalents = static_cast<int64_t>(std::llround(
      flat * static_cast<double>(best->gate_equivalents()) / static_cast<double>(best->cells)));
  e.anchor_key = best->key;
  e.differing_parameters = best_diff % 1000;  // (without the other site's penalty)
  return e;
}

}  // namespace shadesim
