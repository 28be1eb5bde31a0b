// The colour formats: spec_colour, which carries every colour word (ks_c L_c, and kd_c L_c with
// the diffuse colour multiplied), and the specular unit's output format, each within its share
// of the budget and no coarser than the default's.
#pragma once

#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "derive/survey.h"
#include "model/unit_config.h"

namespace shadesim {

// The largest colour product PixelCombine brings into the series format: a colour word times
// the specular intensity (<= 1) or, multiplied, times N.L, whose series overshoots 1 where the
// Taylor expansion does (the largest series value measured).
double colour_product_max(double colour_max, double series_max);

// Each sets its format in cfg and returns why.
std::string derive_spec_colour(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                               UnitConfig& cfg);
std::string derive_specular_out(const std::vector<SceneInfo>& scenes, const ConfigMeasurements& ms,
                                UnitConfig& cfg);

extern const DerivationRule kSpecColourRule, kSpecularOutRule;

}  // namespace shadesim
