// SeriesEngine: the per-pixel forward-difference step of one series, v += d; d += d2 — two
// additions per pixel and no multiplier. Mirrors rtl/series_engine.sv.
//
// The additions follow the series format's overflow rule (wrap, as a plain adder does, or
// saturate). Both additions read the old d, as the RTL's registers do on one clock edge.
#pragma once

#include <cstdint>
#include <vector>

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

// SeriesBank: the unit's series engines side by side (the RTL's generate loop over
// series_engine), stored as arrays so one pixel step touches contiguous memory and the overflow
// rule is chosen once per step, not once per addition. Bit-identical to N SeriesEngines.
class SeriesBank {
 public:
  SeriesBank(const FixedFormat& series, int count)
      : wrap_(series.overflow == Overflow::kWrap),
        offset_(series.raw_max() + 1),
        mask_(static_cast<uint64_t>(series.raw_max()) * 2 + 1),
        max_(series.raw_max()),
        min_(series.raw_min()),
        v_(static_cast<size_t>(count)),
        d_(static_cast<size_t>(count)),
        d2_(static_cast<size_t>(count)) {}

  int size() const { return static_cast<int>(v_.size()); }
  void load(int i, const SeriesStart& s) {
    v_[static_cast<size_t>(i)] = s.v;
    d_[static_cast<size_t>(i)] = s.d;
    d2_[static_cast<size_t>(i)] = s.d2;
  }
  const int64_t* values() const { return v_.data(); }

  void step() {
    const size_t n = v_.size();
    int64_t* v = v_.data();
    int64_t* d = d_.data();
    const int64_t* d2 = d2_.data();
    if (wrap_) {
      // Two's-complement wrap to wl bits: ((x + 2^(wl-1)) mod 2^wl) - 2^(wl-1).
      for (size_t i = 0; i < n; ++i) {
        v[i] = wrap(v[i] + d[i]);
        d[i] = wrap(d[i] + d2[i]);
      }
    } else {
      for (size_t i = 0; i < n; ++i) {
        v[i] = saturate(v[i] + d[i]);
        d[i] = saturate(d[i] + d2[i]);
      }
    }
  }

 private:
  int64_t wrap(int64_t x) const {
    return static_cast<int64_t>((static_cast<uint64_t>(x + offset_)) & mask_) - offset_;
  }
  int64_t saturate(int64_t x) const { return x > max_ ? max_ : (x < min_ ? min_ : x); }

  bool wrap_;
  int64_t offset_;
  uint64_t mask_;
  int64_t max_, min_;
  std::vector<int64_t> v_, d_, d2_;
};

}  // namespace shadesim
