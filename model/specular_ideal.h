// SpecularIdeal: exact pow(t, n) of the fixed-point t, in double, rounded into the specular
// output format. Not hardware: the yardstick the hardware units are measured against, and the
// specular unit used until a hardware one is chosen. Every report labels it "ideal".
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "model/fixed_point.h"

namespace shadesim {

class SpecularIdeal {
 public:
  SpecularIdeal(const FixedFormat& series, const FixedFormat& out) : series_(series), out_(out) {}

  void set_exponent(double n) { exponent_ = n; }

  int64_t operator()(int64_t t_raw) const {
    const double t = std::clamp(series_.to_double(t_raw), 0.0, 1.0);
    return out_.from_double(std::pow(t, exponent_));
  }

 private:
  FixedFormat series_;
  FixedFormat out_;
  double exponent_ = 1.0;
};

}  // namespace shadesim
