// The specular unit: none without a specular term, else the one the scenes' materials name (or
// ideal's hardware substitute), and, where that misses the budget on the scenes (measured), the
// search over the candidates (derive/specular_candidates.h), each with the widths derived for it
// (kSpecularRule).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "derive/survey.h"
#include "host/prepared_scene.h"
#include "model/unit_config.h"

namespace shadesim {

struct SpecularChoice {
  bool substitute = false;  // DerivedConfig::substitute
  std::string why;
};

// Sets cfg.specular: the unit the materials name, ideal's substitute, options.specular_trial, or
// none. Throws std::invalid_argument where the scenes' materials name different units.
SpecularChoice choose_specular_unit(const std::vector<SceneInfo>& scenes,
                                    const DeriveOptions& options, UnitConfig& cfg);

// One unit derived for `options` on the search's scenes (derive_config's, with the gate held).
using DeriveUnit = std::function<DerivedConfig(const DeriveOptions& options)>;

// The unit derive_unit(options) derives, or, where its specular unit misses the budget on the
// scenes and exact pow on its formats would not, the first candidate that meets it (the one
// taken stated on the specular line with every unit tried).
DerivedConfig search_specular_unit(const FrameSet& frames, const DeriveOptions& options,
                                   const DeriveUnit& derive_unit);

extern const DerivationRule kSpecularRule, kWideningRule;

}  // namespace shadesim
