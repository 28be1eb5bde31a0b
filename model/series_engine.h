// SeriesEngine: the per-pixel forward-difference step of one series, v += d; d += d2 — two
// additions per pixel and no multiplier. Mirrors rtl/series_engine.sv (its registers v_q, d_q,
// d2_q: loaded from span setup, stepped once per pixel).
//
// SeriesEngine::step is the one definition of the stepping rule: both additions read the old d,
// as the RTL's registers do on one clock edge, and each sum follows the series format's overflow
// rule (FixedFormat's RawOverflow::fit: wrap, as a plain adder does, or saturate).
#pragma once

#include <cstdint>
#include <vector>

#include "model/fixed_point.h"
#include "model/span_setup.h"

namespace shadesim {

class SeriesEngine {
 public:
  // One clock edge with step_i high, on the registers (v, d, d2) of an engine whose series
  // format has this overflow rule.
  static void step(const RawOverflow& rule, int64_t& v, int64_t& d, int64_t d2) {
    v = rule.fit(v + d);  // |v|, |d|, |d2| < 2^61: no host overflow
    d = rule.fit(d + d2);
  }

  explicit SeriesEngine(const FixedFormat& series) : rule_(series.raw_overflow()) {}

  void load(const SeriesStart& s) { state_ = s; }
  int64_t value() const { return state_.v; }
  const SeriesStart& state() const { return state_; }
  void step() { step(rule_, state_.v, state_.d, state_.d2); }

 private:
  RawOverflow rule_;
  SeriesStart state_;
};

// SeriesBank: a lane's series engines side by side — the RTL's generate loop over series_engine,
// whose v_o outputs form eng_v. Storage only: the engines' registers as arrays, so a pixel reads
// every series value from contiguous memory. Each engine steps by SeriesEngine::step.
class SeriesBank {
 public:
  SeriesBank(const FixedFormat& series, int count)
      : rule_(series.raw_overflow()),
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
    // The rule is the same for every engine: chosen once per step, not once per addition.
    if (rule_.wraps) {
      RawOverflow wrap = rule_;
      for (size_t i = 0; i < n; ++i) SeriesEngine::step(wrap, v[i], d[i], d2[i]);
    } else {
      RawOverflow saturate = rule_;
      for (size_t i = 0; i < n; ++i) SeriesEngine::step(saturate, v[i], d[i], d2[i]);
    }
  }

 private:
  RawOverflow rule_;
  std::vector<int64_t> v_, d_, d2_;
};

}  // namespace shadesim
