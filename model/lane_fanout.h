// LaneFanout: the start of each lane's engines for a unit with K = UnitConfig::lanes pixel lanes
// (rtl/lane_fanout.sv), from the span's (v, d, d2) at its first pixel x0 (SpanSetup's output).
// Lane j shades pixels x0 + j, x0 + j + K, ...: k-step forward differences of the same
// quadratic p(i) = v + i d + i(i-1)/2 d2, so
//
//   v_j = p(j)                    = v + j d + j(j-1)/2 d2
//   D_j = p(j + K) - p(j)         = K d + (K j + K(K-1)/2) d2
//   D2  = p(j + 2K) - 2 p(j + K) + p(j) = K^2 d2
//
// and the lane's SeriesEngine steps v_j += D_j; D_j += D2 once per beat. Each result is formed
// exactly (integers: no rounding) and brought into the series format once by its overflow rule
// (FixedFormat::quantize): with wrap that is exact modulo 2^wl, so every lane's values equal
// the one-lane engine's bit for bit; with saturate each of v_j, D_j, D2 is clamped once here,
// and the engine's additions saturate as before (a span whose series overflow may then differ
// from the one-lane unit, which clamps after every pixel instead).
//
// With K = 1 the fan-out is the identity (v, d, d2).
#pragma once

#include <cstdint>

#include "model/fixed_point.h"
#include "model/span_setup.h"

namespace shadesim {

class LaneFanout {
 public:
  LaneFanout(const FixedFormat& series, int lanes) : series_(series), lanes_(lanes) {}

  int lanes() const { return lanes_; }

  // Lane `lane`'s engine start (0 <= lane < lanes()).
  SeriesStart operator()(const SeriesStart& s, int lane) const {
    const Int128 j = lane, k = lanes_;
    const Int128 v = Int128{s.v} + j * s.d + j * (j - 1) / 2 * s.d2;
    const Int128 d = k * s.d + (k * j + k * (k - 1) / 2) * s.d2;
    const Int128 d2 = k * k * s.d2;
    const int f = series_.frac_bits();  // same format: only the overflow rule applies
    return {series_.quantize(v, f), series_.quantize(d, f), series_.quantize(d2, f)};
  }

 private:
  FixedFormat series_;
  int lanes_;
};

}  // namespace shadesim
