#include "derive/reasons.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "derive/colour_rules.h"
#include "derive/helpers.h"
#include "derive/pipelining.h"
#include "derive/specular_search.h"
#include "derive/survey.h"
#include "derive/width_rules.h"
#include "model/coef_packing.h"
#include "model/command_stream.h"

namespace shadesim {
namespace {

// What the term widths save: read from the final unit, whose span setup decides the layout.
std::string packing_why(const UnitConfig& cfg) {
  const CoefLayout layout = CoefLayout::of(cfg);
  int bits = 0;
  for (int t = 0; t < kTermsPerSeries; ++t) bits += cfg.coef_term_bits(t);
  return std::to_string(bits) + " bits per series, a triangle's " +
         std::to_string(cfg.series_per_triangle()) + " series in " + std::to_string(layout.words) +
         " payload words (" + std::to_string(cfg.series_per_triangle() * kTermsPerSeries) +
         " unpacked)";
}

// The throughput structure's reasons (derive/throughput_choice.h), in config_to_json's order;
// material_buffers and start_depth are listed whether or not the JSON writes them (it leaves
// out their defaults), so a later choice can replace every one (rechoose_throughput).
std::vector<FieldReason> throughput_reasons(const UnitConfig& cfg, const ThroughputChoice& t) {
  const std::string only = " (throughput only: pixels do not depend on it)";
  std::vector<FieldReason> r = {
      {"port_words", std::to_string(cfg.port_words), t.port_words + only},
      {"tri_queue", std::to_string(cfg.tri_queue), t.tri_queue},
      {"lanes", std::to_string(cfg.lanes), t.lanes},
      {"material_buffers", std::to_string(cfg.material_buffers), t.material_buffers},
      {"span_setup", to_string(cfg.span_setup), t.span_setup}};
  if (cfg.host_setup())
    r.push_back({"start_depth", std::to_string(cfg.start_depth),
                 "the start bank's entries: " + t.start_depth});
  return r;
}

// The specular line's value: the unit as the CLI names it, with its output format.
std::string specular_value(const UnitConfig& cfg) {
  return cfg.specular.describe() + (cfg.specular.kind == SpecularUnitKind::kNone
                                        ? std::string()
                                        : " out=" + cfg.specular.out.to_string());
}

// The specular line's note on a Schlick or W_m unit's timing; "" for other units.
constexpr const char* kTimingNote = "; timing ";
std::string timing_why(const ThroughputChoice& t) {
  return t.timing.empty() ? "" : kTimingNote + t.timing + " (throughput only: same bits)";
}

}  // namespace

// The budget's reason, then one per field in config_to_json's order, each value as it writes it.
std::vector<FieldReason> field_reasons(const UnitConfig& cfg, const Budget& budget,
                                       const FieldWhys& why, const ThroughputChoice& throughput) {
  const auto json = nlohmann::json::parse(config_to_json(cfg));
  std::vector<FieldReason> reasons;
  reasons.push_back({"budget", fmt(budget.lsb) + " LSB",
                     "from " + budget.from +
                         "; Taylor error keeps it in setup, the "
                         "fixed-point error gets budget/4 for drift, budget/4 for "
                         "coefficient rounding, 3/16 for the colour words and 1/16 for the "
                         "specular output on top"});
  auto reason = [&json, &reasons](const char* field, const std::string& text) {
    const auto& value = json.at(field);
    reasons.push_back({field, value.is_string() ? value.get<std::string>() : value.dump(), text});
  };
  reason("channels", why.channels);
  reason("lights", why.lights);
  reason("xy_bits", why.xy_bits);
  if (json.contains("offset_bits")) reason("offset_bits", why.offset_bits);
  reason("coef", why.coef);
  reason("coef_term_iwl", why.coef_term_iwl + "; " + packing_why(cfg));
  reason("series", why.series);
  reason("spec_colour", why.spec_colour);
  reason("out_bits", "as requested");
  for (FieldReason& r : throughput_reasons(cfg, throughput)) reasons.push_back(std::move(r));
  reasons.push_back({"diffuse_colour", to_string(cfg.diffuse_colour), why.diffuse_colour});
  reasons.push_back(
      {"specular", specular_value(cfg), why.specular + why.specular_out + timing_why(throughput)});
  return reasons;
}

void rechoose_throughput(const FrameSet& frames, const DeriveOptions& options, DerivedConfig& d) {
  const ThroughputChoice t = choose_throughput(frames, options, d.config);
  d.config = t.config;
  d.cycles_misses = t.misses;
  d.cycles = t.cycles;
  for (FieldReason& fresh : throughput_reasons(d.config, t)) {
    const auto at = std::find_if(d.reasons.begin(), d.reasons.end(),
                                 [&](const FieldReason& r) { return r.field == fresh.field; });
    if (at != d.reasons.end()) {
      *at = std::move(fresh);
    } else {  // start_depth, now with host setup: after span_setup
      const auto site = std::find_if(d.reasons.begin(), d.reasons.end(),
                                     [](const FieldReason& r) { return r.field == "span_setup"; });
      d.reasons.insert(site == d.reasons.end() ? site : site + 1, std::move(fresh));
    }
  }
  if (!d.config.host_setup()) {
    d.reasons.erase(std::remove_if(d.reasons.begin(), d.reasons.end(),
                                   [](const FieldReason& r) { return r.field == "start_depth"; }),
                    d.reasons.end());
  }
  for (FieldReason& r : d.reasons) {
    if (r.field != "specular") continue;
    r.reason = r.reason.substr(0, r.reason.find(kTimingNote)) + timing_why(t);
    r.value = specular_value(d.config);
  }
}

std::vector<DerivationRule> derivation_rules() {
  return {kBudgetRule,     kChannelsRule, kLightsRule,      kXyBitsRule,     kOffsetBitsRule,
          kSeriesRule,     kCoefRule,     kGateRule,        kGainRule,       kCoefTermsRule,
          kSpecColourRule, kOutBitsRule,  kLanesRule,       kThroughputRule, kDiffuseColourRule,
          kSpecularRule,   kWideningRule, kSpecularOutRule, kPipeliningRule};
}

}  // namespace shadesim
