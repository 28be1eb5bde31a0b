// SchlickDivider: Schlick's S = t / (n - n t + t) by a restoring radix-2 divider. Mirrors
// rtl/schlick_divider.sv.
//
// Parameters (SchlickConfig, same names in RTL): Q = quotient_bits (= iterations), D =
// operand_bits (fraction bits of the divider operands), timing (iterative | pipelined). The
// series format (frac bits fs) comes from the unit config. No per-material parameters: the
// exponent lives entirely in the two series, pre-scaled at setup (host/specular_setup):
//   numerator   series = t / n'                (affine in t)
//   denominator series = (n' - (n' - 1) t) / n' (affine in t; n' = n, or a fitted n')
// Scaling both by 1/n' keeps them in [0, 1] for t in [0, 1] without changing the quotient.
//
// Stages:
//   1. CLAMP/ALIGN  num <= 0 -> result 0 (t <= 0). den <= 0 -> result 1 (t beyond 1 where the
//                   denominator crosses zero). Otherwise both are quantized (truncate,
//                   saturate) to unsigned 2.D operands; num_op == 0 -> 0; num_op >= den_op ->
//                   1 (the quotient saturates at 1: t >= 1).
//   2. DIVIDE       restoring radix-2, Q iterations, one quotient bit each:
//                     r <- 2r; if r >= den_op { r <- r - den_op; bit = 1 } else bit = 0
//                   starting from r = num_op < den_op, giving q = floor(num_op * 2^Q / den_op).
//   3. OUTPUT       quantize(q, Q fraction bits) into the specular out format.
// Timing: iterative = one subtract/compare stage reused Q times (one pixel per Q cycles, latency
// Q); pipelined = Q stages (one pixel per cycle, latency Q). Same bits either way.
#pragma once

#include <cstdint>
#include <vector>

#include "model/fixed_point.h"
#include "model/specular_config.h"

namespace shadesim {

class SchlickDivider {
 public:
  SchlickDivider(const SchlickConfig& config, const FixedFormat& series, const FixedFormat& out);

  // No per-material parameters: unit_params must be empty. Throws std::invalid_argument otherwise.
  void load_params(const std::vector<int64_t>& unit_params);

  int64_t evaluate(int64_t num_raw, int64_t den_raw) const;

  // The divider's raw Q-bit quotient for operands already aligned (stage 2 alone; for tests).
  static uint64_t divide(uint64_t num_op, uint64_t den_op, int quotient_bits);

  // --- cost ---
  static int iterations(const SchlickConfig& c) { return c.quotient_bits; }
  static int cycles_per_pixel(const SchlickConfig& c) {
    return c.timing == UnitTiming::kIterative ? c.quotient_bits : 1;
  }
  static int latency(const SchlickConfig& c) { return c.quotient_bits; }
  // Subtract/compare stages of (D + 3) bits in hardware.
  static int subtractor_stages(const SchlickConfig& c) {
    return c.timing == UnitTiming::kIterative ? 1 : c.quotient_bits;
  }

 private:
  SchlickConfig config_;
  FixedFormat series_;
  FixedFormat out_;
  FixedFormat operand_;  // unsigned 2.D, truncate, saturate
};

}  // namespace shadesim
