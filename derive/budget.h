// The error budget: the strictest scene's (or the one asked for), and the share of it each
// fixed-point error gets on top of the Taylor error (kBudgetRule).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "derive/survey.h"

namespace shadesim {

// The largest output-code error a budget allows: codes differ by whole LSBs, and rounding the
// model and the reference each to a code makes 1 LSB of difference from any real error, so a
// budget of B LSB allows ceil(B) (0.9 and 1 both allow 1).
inline int code_budget(double budget_lsb) { return static_cast<int>(std::ceil(budget_lsb)); }

struct Budget {
  double lsb = 0;
  std::string from;  // "--budget" or the scene it is taken from
};

// Throws std::invalid_argument unless lsb is a positive number.
void check_budget(double lsb);
// The strictest scene's budget unless one is given: one unit must meet every scene's.
Budget choose_budget(const std::vector<SceneInfo>& scenes, const DeriveOptions& options);
// The budget and each fixed-point error's share of it.
void set_budget(double lsb, ConfigMeasurements& ms);

extern const DerivationRule kBudgetRule;

}  // namespace shadesim
