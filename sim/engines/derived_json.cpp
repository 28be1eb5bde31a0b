#include "sim/engines/derived_json.h"

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "model/command_stream.h"
#include "model/unit_config_file.h"

namespace shadesim {
namespace {

// Every ConfigMeasurements field with its JSON name, for writing (M const) and reading: one
// list, so the two cannot drift apart. A field added to ConfigMeasurements joins here.
template <class M, class F>
void each_measurement(M& m, F&& f) {
  f("budget_lsb", m.budget_lsb);
  f("max_width", m.max_width);
  f("max_height", m.max_height);
  f("longest_span", m.longest_span);
  f("max_offset", m.max_offset);
  f("start_offset_min", m.start_offset_min);
  f("start_offset_max", m.start_offset_max);
  f("max_monomial_sum", m.max_monomial_sum);
  f("series_min", m.series_min);
  f("series_max", m.series_max);
  f("difference_max", m.difference_max);
  f("colour_max", m.colour_max);
  f("product_max", m.product_max);
  f("coef_max", m.coef_max);
  f("gain", m.gain);
  f("drift_share_lsb", m.drift_share_lsb);
  f("coef_share_lsb", m.coef_share_lsb);
  f("colour_share_lsb", m.colour_share_lsb);
  f("specular_out_share_lsb", m.specular_out_share_lsb);
}

}  // namespace

nlohmann::json derived_to_json(const DerivedConfig& d) {
  nlohmann::json j = nlohmann::json::parse(config_to_json(d.config));
  nlohmann::json reasons = nlohmann::json::array();
  for (const FieldReason& r : d.reasons)
    reasons.push_back({{"field", r.field}, {"value", r.value}, {"reason", r.reason}});
  nlohmann::json cycles = nlohmann::json::array();
  for (const SceneCycles& c : d.cycles) cycles.push_back({c.cycles, c.pixels, c.pixel_beats});
  nlohmann::json measured = nlohmann::json::object();
  each_measurement(d.measured, [&](const char* name, const auto& v) {
    if constexpr (std::is_floating_point_v<std::decay_t<decltype(v)>>) {
      if (!std::isfinite(v))
        throw std::domain_error(std::string("measurement ") + name + " is not finite");
    }
    measured[name] = v;
  });
  j["derivation"] = {{"reasons", reasons},
                     {"measured", measured},
                     {"substitute", d.substitute},
                     {"cycles_misses", d.cycles_misses},
                     {"cycles", cycles}};
  return j;
}

DerivedConfig derived_from_json(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw std::runtime_error(source + ": not a JSON object");
  DerivedConfig d;
  d.config = parse_unit_config(j.dump(), source);  // validates
  try {
    const nlohmann::json& dj = j.at("derivation");
    for (const auto& r : dj.at("reasons"))
      d.reasons.push_back({r.at("field").get<std::string>(), r.at("value").get<std::string>(),
                           r.at("reason").get<std::string>()});
    if (d.reasons.empty()) throw std::runtime_error("no reasons");
    const nlohmann::json& m = dj.at("measured");
    each_measurement(d.measured, [&](const char* name, auto& v) {
      v = m.at(name).get<std::decay_t<decltype(v)>>();
    });
    d.substitute = dj.at("substitute").get<bool>();
    d.cycles_misses = dj.at("cycles_misses").get<std::vector<std::string>>();
    for (const auto& c : dj.at("cycles"))
      d.cycles.push_back(
          {c.at(0).get<uint64_t>(), c.at(1).get<uint64_t>(), c.at(2).get<uint64_t>()});
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(source + ": derivation: " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(source + ": derivation: " + e.what());
  }
  return d;
}

}  // namespace shadesim
