#include "model/schlick_divider.h"

#include <stdexcept>

namespace shadesim {

SchlickDivider::SchlickDivider(const SchlickConfig& config, const FixedFormat& series,
                               const FixedFormat& out)
    : config_(config), series_(series), out_(out) {
  operand_.wl = config.operand_bits + 2;
  operand_.iwl = 2;
  operand_.is_signed = false;
  operand_.quant = Quantization::kTruncate;
  operand_.overflow = Overflow::kSaturate;
}

void SchlickDivider::load_params(const std::vector<int64_t>& unit_params) {
  if (!unit_params.empty()) {
    throw std::invalid_argument("schlick: MATERIAL unit_params must be empty (got " +
                                std::to_string(unit_params.size()) + " words)");
  }
}

uint64_t SchlickDivider::divide(uint64_t num_op, uint64_t den_op, int quotient_bits) {
  uint64_t r = num_op;
  uint64_t q = 0;
  for (int i = 0; i < quotient_bits; ++i) {
    r <<= 1;
    q <<= 1;
    if (r >= den_op) {
      r -= den_op;
      q |= 1;
    }
  }
  return q;
}

int64_t SchlickDivider::evaluate(int64_t num_raw, int64_t den_raw) const {
  // 1. CLAMP/ALIGN
  if (num_raw <= 0) return 0;
  if (den_raw <= 0) return out_.quantize(1, 0);
  const int64_t num_op = operand_.quantize(num_raw, series_.frac_bits());
  const int64_t den_op = operand_.quantize(den_raw, series_.frac_bits());
  if (num_op == 0) return 0;
  if (num_op >= den_op) return out_.quantize(1, 0);
  // 2. DIVIDE
  const uint64_t q =
      divide(static_cast<uint64_t>(num_op), static_cast<uint64_t>(den_op), config_.quotient_bits);
  // 3. OUTPUT
  return out_.quantize(static_cast<Int128>(q), config_.quotient_bits);
}

}  // namespace shadesim
