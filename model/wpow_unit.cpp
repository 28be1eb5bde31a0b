#include "model/wpow_unit.h"

#include <stdexcept>
#include <string>

namespace shadesim {

int WpowUnit::stages(const WpowConfig& c) {
  int k = 0;
  while ((1 << k) < c.max_m) ++k;
  return k;
}

WpowUnit::WpowUnit(const WpowConfig& config, const FixedFormat& series, const FixedFormat& out)
    : config_(config), series_(series), out_(out), stages_(stages(config)), squarings_(stages_) {
  base_.wl = config.base_bits + 1;
  base_.iwl = 1;
  base_.is_signed = false;
  base_.quant = Quantization::kTruncate;
  base_.overflow = Overflow::kSaturate;
}

void WpowUnit::load_params(const std::vector<int64_t>& unit_params) {
  if (unit_params.empty()) {
    shift_ = 0;
    squarings_ = stages_;
    return;
  }
  if (unit_params.size() != 2 || unit_params[0] < 0 || unit_params[0] > series_.frac_bits() ||
      unit_params[1] < 0 || unit_params[1] > stages_) {
    throw std::invalid_argument("wpow: MATERIAL unit_params must be [shift 0.." +
                                std::to_string(series_.frac_bits()) + ", squarings 0.." +
                                std::to_string(stages_) + "]");
  }
  shift_ = static_cast<int>(unit_params[0]);
  squarings_ = static_cast<int>(unit_params[1]);
}

int64_t WpowUnit::evaluate(int64_t series_raw) const {
  const int b_frac = config_.base_bits;
  const int64_t one = int64_t{1} << b_frac;
  // 0. BASE: shift, saturate to [0, 2), clamp to 1.
  int64_t b = base_.quantize(series_raw, series_.frac_bits() - shift_);
  if (b > one) b = one;
  // 1..K. SQUARE (the first K - s stages bypass)
  for (int k = 0; k < squarings_; ++k) b = base_.quantize(Int128{b} * b, 2 * b_frac);
  // K+1. OUTPUT
  return out_.quantize(b, b_frac);
}

}  // namespace shadesim
