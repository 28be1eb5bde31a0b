// SeriesEngine: the per-pixel forward-difference step of one series, v += d; d += d2 — two
// additions per pixel and no multiplier. Mirrors rtl/series_engine.sv.
//
// The additions follow the series format's overflow rule (wrap, as a plain adder does, or
// saturate). Both additions read the old d, as the RTL's registers do on one clock edge.
#pragma once

#include <cstdint>

#include "model/fixed_point.h"
#include "model/span_setup.h"

namespace shadesim {

class SeriesEngine {
 public:
  explicit SeriesEngine(const FixedFormat& series)
      : wrap_(series.overflow == Overflow::kWrap),
        shift_(64 - series.wl),
        max_(series.raw_max()),
        min_(series.raw_min()) {}

  void load(const SeriesStart& s) { state_ = s; }
  int64_t value() const { return state_.v; }
  const SeriesStart& state() const { return state_; }

  void step() {
    state_.v = add(state_.v, state_.d);
    state_.d = add(state_.d, state_.d2);
  }

  int64_t add(int64_t a, int64_t b) const {
    const int64_t s = a + b;  // |a|,|b| < 2^61: no host overflow
    if (wrap_) return static_cast<int64_t>(static_cast<uint64_t>(s) << shift_) >> shift_;
    return s > max_ ? max_ : (s < min_ ? min_ : s);
  }

 private:
  bool wrap_;
  int shift_;
  int64_t max_, min_;
  SeriesStart state_;
};

}  // namespace shadesim
