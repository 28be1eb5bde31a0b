#include "model/fixed_point.h"

#include <cmath>
#include <sstream>

namespace shadesim {

void FixedFormat::validate(const std::string& what) const {
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(what + ": fixed-point format " + to_string() + " " + why);
  };
  if (wl < 1 || wl > 62) fail("needs a word length from 1 to 62 bits");
  if (is_signed && wl < 2) fail("is signed and needs at least 2 bits");
  if (frac_bits() < 0 || frac_bits() > 60) fail("needs 0 to 60 fraction bits");
}

int64_t FixedFormat::quantize(Int128 raw, int src_frac) const {
  int drop = src_frac - frac_bits();
  if (drop > 120) {
    // Everything below the LSB: only the sign (for truncation) survives. Reduce to an equivalent
    // 120-bit drop so the shifts below stay defined.
    raw = raw < 0 ? -(Int128{1} << 119) : (raw > 0 ? Int128{1} : Int128{0});
    drop = 120;
  }
  Int128 v;
  if (drop > 0) {
    if (quant == Quantization::kRoundNearest) raw += Int128{1} << (drop - 1);
    v = floor_shift_right(raw, drop);
  } else if (-drop >= 64 && raw != 0) {
    // Shifted past every bit of the word: wrap leaves zeros, saturation keeps only the sign.
    if (overflow == Overflow::kWrap) return 0;
    return raw > 0 ? raw_max() : raw_min();
  } else {
    v = shift_left(raw, -drop);
  }
  return fit(v);
}

int64_t FixedFormat::from_double(double x) const {
  if (std::isnan(x)) throw std::invalid_argument("FixedFormat::from_double: NaN");
  if (std::isinf(x)) return x > 0 ? raw_max() : raw_min();
  // The encoder's hot path, the same rule: x 2^F is exact (a power-of-two scale that neither
  // overflows nor underflows here), floor() is truncation's shift, and adding 1/2 is exact
  // while |x 2^F| < 2^52 (at or beyond it x 2^F is already an integer). Anything else takes
  // the general route below.
  const int frac = frac_bits();
  if (frac >= 0 && frac <= 62) {
    const double scaled = x * static_cast<double>(int64_t{1} << frac);
    constexpr double kExactHalf = 4503599627370496.0;  // 2^52
    constexpr double kInt64 = 4611686018427387904.0;   // 2^62
    if (std::fabs(scaled) < kInt64) {
      const double integer = quant == Quantization::kRoundNearest && std::fabs(scaled) < kExactHalf
                                 ? std::floor(scaled + 0.5)
                                 : std::floor(scaled);
      return fit(Int128{static_cast<int64_t>(integer)});
    }
  }
  // x = mantissa * 2^-src_frac exactly, with a 53-bit integer mantissa.
  int exponent = 0;
  const double fraction = std::frexp(x, &exponent);
  const auto mantissa = static_cast<int64_t>(std::ldexp(fraction, 53));
  const int src_frac = 53 - exponent;
  if (src_frac < -60) return quantize(mantissa > 0 ? (Int128{1} << 120) : -(Int128{1} << 120), 0);
  return quantize(mantissa, src_frac);
}

double FixedFormat::to_double(int64_t raw) const {
  return std::ldexp(static_cast<double>(raw), -frac_bits());
}

std::string FixedFormat::to_string() const {
  std::ostringstream os;
  os << (is_signed ? 's' : 'u') << iwl << '.' << frac_bits();
  if (quant == Quantization::kRoundNearest) os << ":rnd";
  if (overflow == Overflow::kSaturate) os << ":sat";
  return os.str();
}

FixedFormat parse_fixed_format(const std::string& text, const std::string& what) {
  auto fail = [&]() -> FixedFormat {
    throw std::invalid_argument(
        what + ": cannot read fixed-point format '" + text +
        "'; expected s<int>.<frac> or u<int>.<frac>, optionally followed by :trn|:rnd and "
        ":sat|:wrap (e.g. s4.28, u1.16:rnd:sat)");
  };
  if (text.size() < 4 || (text[0] != 's' && text[0] != 'u')) return fail();
  FixedFormat f;
  f.overflow = Overflow::kWrap;  // a format without :sat/:wrap wraps, as SystemC's sc_fix does
  f.is_signed = text[0] == 's';
  std::string rest = text.substr(1);
  std::string suffix;
  if (const auto colon = rest.find(':'); colon != std::string::npos) {
    suffix = rest.substr(colon);
    rest = rest.substr(0, colon);
  }
  const auto dot = rest.find('.');
  if (dot == std::string::npos) return fail();
  try {
    size_t used = 0;
    const int iwl = std::stoi(rest.substr(0, dot), &used);
    if (used != dot) return fail();
    const std::string frac_text = rest.substr(dot + 1);
    const int frac = std::stoi(frac_text, &used);
    if (used != frac_text.size() || frac < 0) return fail();
    f.iwl = iwl;
    f.wl = iwl + frac;
  } catch (const std::logic_error&) {
    return fail();
  }
  while (!suffix.empty()) {
    const auto next = suffix.find(':', 1);
    const std::string tok =
        suffix.substr(1, next == std::string::npos ? std::string::npos : next - 1);
    if (tok == "trn")
      f.quant = Quantization::kTruncate;
    else if (tok == "rnd")
      f.quant = Quantization::kRoundNearest;
    else if (tok == "sat")
      f.overflow = Overflow::kSaturate;
    else if (tok == "wrap")
      f.overflow = Overflow::kWrap;
    else
      return fail();
    suffix = next == std::string::npos ? std::string() : suffix.substr(next);
  }
  f.validate(what);
  return f;
}

}  // namespace shadesim
