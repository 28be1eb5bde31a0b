#include "sim/eda/sta/sta_constraints.h"

#include <fmt/format.h>

#include <map>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/tool_script.h"

namespace shadesim {
namespace {

using Json = nlohmann::json;

// The library's smallest-area buffer: a one-input cell whose one output equals its input. A
// small buffer is what a neighbouring block's register would drive a port through.
const LibertyCell& smallest_buffer(const LibertyLibrary& lib) {
  const LibertyCell* best = nullptr;
  for (const auto& [name, c] : lib.cells) {
    if (c.sequential || c.dont_use || c.inputs().size() != 1 || c.outputs().size() != 1) continue;
    const LibertyPin& in = *c.inputs()[0];
    const std::string& f = c.outputs()[0]->function;
    if (f != in.name && f != "(" + in.name + ")") continue;
    if (!best || c.area < best->area) best = &c;
  }
  if (!best) throw std::runtime_error(lib.path + ": library " + lib.name + " has no buffer cell");
  return *best;
}

}  // namespace

ResolvedConstraints resolve_constraints(const StaConstraints& policy, const LibertyLibrary& lib,
                                        double clock_to_q_ns, double setup_ns) {
  ResolvedConstraints c;
  c.policy = policy;
  const LibertyCell& buffer = smallest_buffer(lib);
  c.driving_cell = buffer.name;
  c.driving_pin = buffer.outputs()[0]->name;
  const PlainFlipFlop ff =
      required_plain_flip_flop(lib, "the ports' load and delays are taken from one");
  c.load_cell = ff.cell->name;
  c.load_pin = ff.d;
  c.output_load_pf = policy.load_pins * ff.cell->pin(ff.d)->capacitance;
  c.input_delay_ns = clock_to_q_ns;
  c.output_delay_ns = setup_ns;
  return c;
}

double required_fmax_mhz(double mhz, const StaConstraints& policy) {
  return mhz / (1.0 - policy.guard_band);
}

std::string constraints_template() {
  return read_text_file(source_dir() + "/sim/eda/sta/constraints.tcl");
}

std::string constraints_tcl(const ResolvedConstraints& c, double period_ns,
                            const std::string& clock) {
  return fill_placeholders(constraints_template(),
                           {{"@PERIOD@", fmt::format("{:g}", period_ns)},
                            {"@CLOCK@", clock},
                            {"@UNCERTAINTY@", fmt::format("{:g}", c.policy.clock_uncertainty_ns)},
                            {"@INPUT_DELAY@", fmt::format("{:.4f}", c.input_delay_ns)},
                            {"@DRIVING_CELL@", c.driving_cell},
                            {"@DRIVING_PIN@", c.driving_pin},
                            {"@OUTPUT_DELAY@", fmt::format("{:.4f}", c.output_delay_ns)},
                            {"@OUTPUT_LOAD@", fmt::format("{:.6f}", c.output_load_pf)}});
}

std::string describe_constraints(const ResolvedConstraints& c) {
  return fmt::format(
      "clock uncertainty {:g} ns; inputs driven by {} after {:.3f} ns ({}'s clock-to-Q); "
      "outputs load {:.1f} fF ({} x {}/{}) due {:.3f} ns before the edge ({}'s setup); "
      "meets = Fmax >= clock / (1 - {:g})",
      c.policy.clock_uncertainty_ns, c.driving_cell, c.input_delay_ns, c.load_cell,
      1000.0 * c.output_load_pf, c.policy.load_pins, c.load_cell, c.load_pin, c.output_delay_ns,
      c.load_cell, c.policy.guard_band);
}

Json constraints_to_json(const ResolvedConstraints& c) {
  return {{"clock_uncertainty_ns", c.policy.clock_uncertainty_ns},
          {"guard_band", c.policy.guard_band},
          {"input_driving_cell", c.driving_cell},
          {"input_driving_pin", c.driving_pin},
          {"input_delay_ns", c.input_delay_ns},
          {"output_load_pf", c.output_load_pf},
          {"output_load_cell", c.load_cell},
          {"output_load_pin", c.load_pin},
          {"output_load_pins", c.policy.load_pins},
          {"output_delay_ns", c.output_delay_ns}};
}

ResolvedConstraints constraints_from_json(const Json& j, const std::string& source) {
  try {
    ResolvedConstraints c;
    c.policy.clock_uncertainty_ns = j.at("clock_uncertainty_ns");
    c.policy.guard_band = j.at("guard_band");
    c.policy.load_pins = j.at("output_load_pins");
    c.driving_cell = j.at("input_driving_cell");
    c.driving_pin = j.at("input_driving_pin");
    c.input_delay_ns = j.at("input_delay_ns");
    c.output_load_pf = j.at("output_load_pf");
    c.load_cell = j.at("output_load_cell");
    c.load_pin = j.at("output_load_pin");
    c.output_delay_ns = j.at("output_delay_ns");
    return c;
  } catch (const Json::exception& e) {
    throw std::runtime_error(source + ": constraints: " + e.what());
  }
}

}  // namespace shadesim
