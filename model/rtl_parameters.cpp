#include "model/rtl_parameters.h"

#include <cstdio>
#include <stdexcept>

#include "model/cycle_model.h"
#include "model/specular_units.h"

namespace shadesim {
namespace {

// The RTL's integer codes for the model's enums (rtl/shade_unit.sv documents each).
int64_t code(Quantization q) { return q == Quantization::kRoundNearest ? 1 : 0; }
int64_t code(Overflow o) { return o == Overflow::kWrap ? 1 : 0; }

}  // namespace

std::vector<VerilogParameter> shade_unit_parameters(const UnitConfig& u) {
  u.validate();
  const SpecularConfig& s = u.specular;
  const SpecularUnitDescriptor& unit = specular_unit(s.kind);
  std::vector<VerilogParameter> p = {
      {"CHANNELS", u.channels},
      {"LIGHTS", u.lights},
      {"XY_BITS", u.xy_bits},
      {"COEF_WL", u.coef.wl},
      {"COEF_IWL", u.coef.iwl},
      {"SERIES_WL", u.series.wl},
      {"SERIES_IWL", u.series.iwl},
      {"SERIES_QUANT", code(u.series.quant)},
      {"SERIES_OVERFLOW", code(u.series.overflow)},
      {"SPEC_COLOUR_WL", u.spec_colour.wl},
      {"SPEC_COLOUR_IWL", u.spec_colour.iwl},
      {"OUT_BITS", u.out_bits},
      {"SPECULAR_KIND", unit.verilog_kind},
      {"SPECULAR_OUT_WL", s.out.wl},
      {"SPECULAR_OUT_IWL", s.out.iwl},
      {"PORT_WORDS", u.port_words},
      {"TRI_QUEUE", u.tri_queue},
      {"LANES", u.lanes},
  };
  // shade_unit's default is 1: one-buffer units keep their parameter list (and build key).
  if (u.material_buffers != 1) p.push_back({"MATERIAL_BUFFERS", u.material_buffers});
  // Likewise OFS_BITS, whose default is the screen-sized 17.
  // (Host span setup has no span setup to size: the offsets and terms size no hardware.)
  if (u.offset_bits != UnitConfig::kMaxOffsetBits && !u.host_setup())
    p.push_back({"OFS_BITS", u.offset_bits});
  // Host span setup (shade_pkg::SetupHost = 1); unit-setup units keep their parameter list.
  if (u.host_setup()) {
    p.push_back({"SPAN_SETUP", 1});
    p.push_back({"START_DEPTH", u.start_depth});
  }
  // Diffuse colour multiply; units that roll the colour into the series keep their list.
  if (u.diffuse_multiply()) p.push_back({"DIFFUSE_MULTIPLY", 1});
  // Pipelining; unpipelined units keep their list.
  if (u.combine_stages != 0) p.push_back({"COMBINE_STAGES", u.combine_stages});
  // Narrowed coefficient terms (coef packing); shade_unit's defaults are COEF_WL.
  if (!u.coef_term_iwl.empty() && !u.host_setup()) {
    for (int t = 0; t < 6; ++t)
      p.push_back({"COEF_T" + std::to_string(t) + "_WL", u.coef_term_bits(t)});
  }
  // Only the selected unit's parameters: the others keep shade_unit's defaults, so two configs
  // that differ in an unused unit's widths map to the same build. The ideal unit and none have
  // no output stage to round and no fields.
  if (unit.hardware) {
    p.push_back({"SPECULAR_OUT_QUANT", code(s.out.quant)});
    p.push_back({"SPECULAR_OUT_OVERFLOW", code(s.out.overflow)});
  }
  // The unit's own fields that are hardware (model/specular_units.h), each in its slot; an enum's
  // code is its Verilog code. Unused slots are 0.
  if (unit.hardware) {
    VerilogParameter packed{"SPEC_PARAMS", std::vector<int64_t>(kSpecSlots, 0)};
    for (const SpecularField& field : unit.fields) {
      if (field.slot < 0) continue;
      if (field.slot >= kSpecSlots)
        throw std::logic_error(unit.field_name(field) + ": slot " + std::to_string(field.slot) +
                               " is beyond SPEC_PARAMS's " + std::to_string(kSpecSlots));
      packed.slots[static_cast<size_t>(field.slot)] = field.get(s);
    }
    p.push_back(packed);
  }
  return p;
}

std::string VerilogParameter::literal() const {
  if (slots.empty()) return std::to_string(value);
  std::string hex;
  for (auto it = slots.rbegin(); it != slots.rend(); ++it) {
    if (*it < 0 || *it > 0xFFFFFFFF)
      throw std::logic_error(name + ": slot value " + std::to_string(*it) + " is not 32-bit");
    char digits[9];
    std::snprintf(digits, sizeof digits, "%08llx", static_cast<unsigned long long>(*it));
    hex += digits;
  }
  return std::to_string(slots.size() * kSpecSlotBits) + "'h" + hex;
}

std::map<std::string, int64_t> parameter_map(const std::vector<VerilogParameter>& params) {
  std::map<std::string, int64_t> m;
  for (const auto& p : params) {
    if (p.slots.empty()) m[p.name] = p.value;
    for (size_t k = 0; k < p.slots.size(); ++k)
      m[p.name + "[" + std::to_string(k) + "]"] = p.slots[k];
  }
  return m;
}

std::vector<std::string> verilator_parameter_args(const std::vector<VerilogParameter>& params) {
  std::vector<std::string> args;
  args.reserve(params.size());
  for (const auto& p : params) args.push_back("-G" + p.name + "=" + p.literal());
  return args;
}

std::vector<std::string> iverilog_parameter_args(const std::vector<VerilogParameter>& params,
                                                 const std::string& root_module) {
  std::vector<std::string> args;
  args.reserve(params.size());
  for (const auto& p : params) {
    args.push_back("-P" + root_module + "." + p.name + "=" + p.literal());
  }
  return args;
}

std::string yosys_chparam_args(const std::vector<VerilogParameter>& params) {
  std::string s;
  for (const auto& p : params) {
    s += (s.empty() ? "" : " ") + std::string("-set ") + p.name + " " + p.literal();
  }
  return s;
}

}  // namespace shadesim
