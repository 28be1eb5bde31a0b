// SpanSetup: start value and differences of one series for one span, from the triangle's
// quantized Taylor coefficients. Mirrors rtl/span_setup.sv stage for stage, in Horner form (every
// multiplier has one offset operand, none a square):
//
//   stage 1  exact brackets with the integer offsets dx = x0 - xo, dy = y - yo (offset_bits
//            signed bits, UnitConfig::offset_bits)
//              a = T1 + T3 dy + T4 dx,   b = T2 + T5 dx
//              d = T2 + T4 dy + T5 (2 dx + 1)                          first forward difference
//   stage 2  exact sums (coef fraction bits, wide enough that nothing is lost)
//              v  = T0 + a dy + b dx                                   value at the first pixel
//                 = T0 + T1 dy + T2 dx + T3 dy^2 + T4 dx dy + T5 dx^2
//              d2 = 2 T5                                               second difference
//   stage 3  each rounded once into the series format (its quantization and overflow rule)
//
// Only stage 3 loses bits, so with truncation the per-pixel value after k steps differs from the
// exact quantized quadratic by at most 2^-F (1 + k + k(k-1)/2): the drift bound (README
// "Checked numerical facts").
#pragma once

#include <cstdint>

#include "model/fixed_point.h"

namespace shadesim {

struct SeriesStart {
  int64_t v = 0, d = 0, d2 = 0;  // series format raw
};

class SpanSetup {
 public:
  SpanSetup(const FixedFormat& coef, const FixedFormat& series, int offset_bits)
      : coef_(coef),
        series_(series),
        offset_{offset_bits, offset_bits, true, Quantization::kTruncate, Overflow::kWrap} {}

  // t[0..5] = T0..T5 raw in the coef format; dx, dy the span's offsets from the origin, taken
  // modulo 2^offset_bits as signed values, as the RTL's OFS_W-bit subtraction does
  // (CommandStream::validate rejects streams whose offsets do not fit).
  SeriesStart operator()(const int64_t* t, int32_t dx, int32_t dy) const {
    const Int128 x = offset_.wrap(int64_t{dx}), y = offset_.wrap(int64_t{dy});
    // Stage 1.
    const Int128 a = Int128{t[1]} + Int128{t[3]} * y + Int128{t[4]} * x;
    const Int128 b = Int128{t[2]} + Int128{t[5]} * x;
    const Int128 d = Int128{t[2]} + Int128{t[4]} * y + Int128{t[5]} * (2 * x + 1);
    // Stage 2.
    const Int128 v = Int128{t[0]} + a * y + b * x;
    const Int128 d2 = 2 * Int128{t[5]};
    const int f = coef_.frac_bits();
    return {series_.quantize(v, f), series_.quantize(d, f), series_.quantize(d2, f)};
  }

 private:
  FixedFormat coef_;
  FixedFormat series_;
  FixedFormat offset_;  // the offsets: offset_bits signed integer bits, wrapping
};

}  // namespace shadesim
