// WpowUnit: W_m(t) = (zeta (t - 1) + 1)^m by repeated squaring (Romanyuk et al.). Mirrors
// rtl/wpow_unit.sv.
//
// Parameters (WpowConfig, same names in RTL): K = log2(max_m) squaring stages, B = base_bits
// (fraction bits of the base and of every square), timing (pipelined | iterative). The series
// format (frac bits fs) comes from the unit config.
// Per material (MATERIAL unit_params): [0] = shift (0..fs), [1] = squarings s (0..K): the unit
// computes base^(2^s). Setup picks s so that the effective m = 2^s <= n (W_m's zero (n - m)/n
// then lies in [0, 1)), and pre-scales the series to x = (zeta (t - 1) + 1) * 2^-shift so the
// large negative bases far from the highlight (zeta up to n/4 = 250) fit the series format.
//
// Stages:
//   0. BASE     b = quantize(series << shift, to unsigned 1.B, truncate, saturate), then
//               b = min(b, 1.0). The clamp is correctness: below t = (n - m)/n the base is
//               negative and an even power would make it large and positive; saturation sends
//               it to 0 instead. Above t = 1 it sends it to 1.
//   1..K. SQUARE_k  b = quantize(b * b, 2B fraction bits -> unsigned 1.B, truncate). Stages
//               1..K-s pass b through unchanged (a bypass mux), the last s square.
//   K+1. OUTPUT quantize(b, B fraction bits) into the specular out format.
// Timing: pipelined = K (B+1)x(B+1) squarers, one pixel per cycle, latency K + 1 (base register
// plus one per squaring stage), or 2K + 1 with square_stages 2 (SQUARE_k in two cycles: b = h 2^H
// + l, H = (B+1)/2; first h^2, l^2 and h l, then h^2 2^2H + l^2 + h l 2^(H+1), the same square);
// iterative = one squarer on one working register (loaded with the
// base, then K steps), one pixel per K + 1 cycles, latency K + 1: the result stays in the
// register until the next pixel starts, as with the iterative divider. Same bits either way.
#pragma once

#include <cstdint>
#include <vector>

#include "model/fixed_point.h"
#include "model/specular_config.h"

namespace shadesim {

class WpowUnit {
 public:
  WpowUnit(const WpowConfig& config, const FixedFormat& series, const FixedFormat& out);

  // unit_params = [shift, squarings]; empty means [0, K]. Throws std::invalid_argument.
  void load_params(const std::vector<int64_t>& unit_params);

  int64_t evaluate(int64_t series_raw) const;

  int squarings() const { return squarings_; }

  // --- cost ---
  static int stages(const WpowConfig& c);  // K = log2(max_m)
  static int multipliers(const WpowConfig& c) {
    return c.timing == UnitTiming::kPipelined ? stages(c) : (stages(c) > 0 ? 1 : 0);
  }
  static int cycles_per_pixel(const WpowConfig& c) {
    return c.timing == UnitTiming::kPipelined ? 1 : stages(c) + 1;
  }
  static int latency(const WpowConfig& c) {
    return stages(c) * (c.timing == UnitTiming::kPipelined ? c.square_stages : 1) + 1;
  }

 private:
  WpowConfig config_;
  FixedFormat series_;
  FixedFormat out_;
  FixedFormat base_;  // unsigned 1.B, truncate, saturate
  int stages_;
  int shift_ = 0;
  int squarings_;
};

}  // namespace shadesim
