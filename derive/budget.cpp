#include "derive/budget.h"

#include <stdexcept>

#include "derive/helpers.h"

namespace shadesim {
namespace {

// Shares of the budget (output LSBs) the fixed-point error may add to the Taylor error.
constexpr double kDriftShare = 0.25;
constexpr double kCoefShare = 0.25;
// Shares for the colour words' rounding and the specular unit's output truncation (3/16 and
// 1/16), so the fixed-point error adds at most 3/4 of the budget to the Taylor error.
constexpr double kColourShare = 0.1875;
constexpr double kSpecularOutShare = 0.0625;

}  // namespace

void check_budget(double lsb) {
  if (!(lsb > 0) || !std::isfinite(lsb)) {
    throw std::invalid_argument("derive_config: budget must be a positive number of LSBs, got " +
                                fmt(lsb));
  }
}

const DerivationRule kBudgetRule = {
    "budget",
    "the smallest error_budget_lsb of the scenes (one unit meets every scene's), or --budget. "
    "The Taylor error keeps the whole budget in setup (subdivision); the fixed-point error gets "
    "budget/4 for drift, budget/4 for coefficient rounding, 3/16 for the colour words and 1/16 "
    "for the specular output on top, so the real error stays below 1.75 budget + output "
    "rounding. The shares bound the worst case; what counts is measured (config shades every "
    "scene on the unit)"};

Budget choose_budget(const std::vector<SceneInfo>& scenes, const DeriveOptions& options) {
  Budget budget;
  if (options.budget_lsb) {
    budget = {*options.budget_lsb, "--budget"};
  } else {
    budget = {scenes.front().scene.error_budget_lsb, scenes.front().path};
    for (const auto& s : scenes) {
      if (s.scene.error_budget_lsb < budget.lsb) budget = {s.scene.error_budget_lsb, s.path};
    }
  }
  check_budget(budget.lsb);
  return budget;
}

// The budget and each fixed-point error's share of it.
void set_budget(double lsb, ConfigMeasurements& ms) {
  ms.budget_lsb = lsb;
  ms.drift_share_lsb = kDriftShare * lsb;
  ms.coef_share_lsb = kCoefShare * lsb;
  ms.colour_share_lsb = kColourShare * lsb;
  ms.specular_out_share_lsb = kSpecularOutShare * lsb;
}

}  // namespace shadesim
