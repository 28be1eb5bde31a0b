// The width rules: xy_bits, span setup's offsets, the series and coefficient formats and the
// coefficient terms' widths, each from the survey and the trial unit's measurements within the
// budget's shares; and G, the gain of the series into an output channel, which the series and
// coefficient rules share.
#pragma once

#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "derive/survey.h"
#include "derive/trial_unit.h"
#include "model/unit_config.h"

namespace shadesim {

struct Gain {
  double total = 0;
  std::string detail;  // each light's (diffuse + specular), for the series' reason
};

// Gain of the series into one output channel: every light's errors add up in it (kGainRule).
Gain series_gain(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg);

// Each sets its fields of cfg (and the measurements it reads on the way) and returns why.
std::string derive_xy_bits(const std::vector<SceneInfo>& scenes, UnitConfig& cfg,
                           ConfigMeasurements& ms);
std::string derive_offset_bits(const Walk& w, UnitConfig& cfg);
std::string derive_series(const std::vector<SceneInfo>& scenes, const Walk& w,
                          ConfigMeasurements& ms, UnitConfig& cfg);
std::string derive_coef(const Walk& w, const ConfigMeasurements& ms, UnitConfig& cfg);
std::string derive_term_widths(const Walk& w, UnitConfig& cfg);

// The fraction bits F the drift bound asks for: the smallest F with
// gain * 2^-F (1 + L(L-1)/2) [/ 2 when rounding] <= share_lsb * 2^-out_bits.
int drift_fraction_bits(int longest_span, double gain, double share_lsb, int out_bits,
                        bool rounding);

extern const DerivationRule kXyBitsRule, kOffsetBitsRule, kSeriesRule, kCoefRule, kGainRule,
    kCoefTermsRule;

}  // namespace shadesim
