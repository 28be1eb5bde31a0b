// Fixed-point formats and the one place where quantization and overflow rules live.
//
// Conventions follow IEEE 1666 (SystemC sc_fix / sc_ufix) so that sc_fix can serve as the
// independent oracle in tests:
//   wl  = total word length in bits (including the sign bit for signed formats)
//   iwl = integer word length (including the sign bit for signed formats); may be negative
//         or larger than wl
//   frac_bits() = wl - iwl
// A value is held as a raw two's-complement integer `raw`, meaning raw * 2^-frac_bits().
//
// The RTL mirrors these rules in rtl/fixed_round.sv (round/truncate) and rtl/fixed_sat.sv
// (saturate/wrap); keep the two in step.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace shadesim {

enum class Quantization {
  kTruncate,      // floor toward -inf (sc_fix SC_TRN): drop the low bits
  kRoundNearest,  // add half an LSB, then floor (sc_fix SC_RND: ties toward +inf)
};

enum class Overflow {
  kSaturate,  // clamp to the representable range (sc_fix SC_SAT)
  kWrap,      // keep the low wl bits, two's complement (sc_fix SC_WRAP)
};

using Int128 = __int128;

// A format's overflow rule with its constants worked out once (FixedFormat::raw_overflow()), for
// a loop over many values of one format (SeriesBank); FixedFormat::wrap / saturate / fit are
// these. On a raw value already at the format's fraction bits:
//   wrap      keep the low wl bits, two's complement: ((raw + 2^(wl-1)) mod 2^wl) - 2^(wl-1)
//             for signed formats, raw mod 2^wl for unsigned ones (a plain adder's carry-out
//             dropped). Branch-free, so a loop of them vectorizes.
//   saturate  clamp to [min, max]
//   fit       the format's own rule
struct RawOverflow {
  uint64_t offset = 0;  // 2^(wl-1) for signed formats, 0 for unsigned ones
  uint64_t mask = 0;    // 2^wl - 1
  int64_t min = 0, max = 0;
  bool wraps = false;

  template <typename Int>
  constexpr int64_t wrap(Int raw) const {
    return static_cast<int64_t>((static_cast<uint64_t>(raw) + offset) & mask) -
           static_cast<int64_t>(offset);
  }
  template <typename Int>
  constexpr int64_t saturate(Int raw) const {
    if (raw > static_cast<Int>(max)) return max;
    if (raw < static_cast<Int>(min)) return min;
    return static_cast<int64_t>(raw);
  }
  template <typename Int>
  constexpr int64_t fit(Int raw) const {
    return wraps ? wrap(raw) : saturate(raw);
  }
};

struct FixedFormat {
  int wl = 32;
  int iwl = 4;
  bool is_signed = true;
  Quantization quant = Quantization::kTruncate;
  Overflow overflow = Overflow::kSaturate;

  constexpr int frac_bits() const { return wl - iwl; }

  constexpr int64_t raw_max() const {
    return is_signed ? (int64_t{1} << (wl - 1)) - 1 : (int64_t{1} << wl) - 1;
  }
  constexpr int64_t raw_min() const { return is_signed ? -(int64_t{1} << (wl - 1)) : 0; }

  // The overflow rules alone, on a raw value already at this format's fraction bits (nothing to
  // drop): inline, for the per-pixel path. quantize(raw, frac_bits()) == fit(raw). `Int` is
  // int64_t or Int128. See RawOverflow.
  constexpr RawOverflow raw_overflow() const;
  template <typename Int>
  constexpr int64_t wrap(Int raw) const;
  template <typename Int>
  constexpr int64_t saturate(Int raw) const;
  template <typename Int>
  constexpr int64_t fit(Int raw) const;
  // Whether `raw` is representable (fit leaves it unchanged).
  constexpr bool holds(int64_t raw) const { return raw >= raw_min() && raw <= raw_max(); }

  // Throws std::invalid_argument with a message naming `what` when the format is unusable.
  void validate(const std::string& what) const;

  // Quantize a raw value that carries `src_frac` fractional bits into this format: first the
  // quantization rule (only when bits are dropped), then the overflow rule. This is the single
  // definition every model class uses; RTL mirrors it.
  int64_t quantize(Int128 raw, int src_frac) const;

  // Quantize a double. Exact for |x| < 2^62 * 2^-src_frac, which covers every format we allow.
  int64_t from_double(double x) const;

  double to_double(int64_t raw) const;

  // Short text form, e.g. "s4.28" (signed, 4 integer bits incl. sign, 28 fraction: truncate and
  // wrap, sc_fix's defaults) or "u1.16:rnd:sat": a suffix for each mode that is not sc_fix's.
  std::string to_string() const;
};

constexpr RawOverflow FixedFormat::raw_overflow() const {
  return {is_signed ? uint64_t{1} << (wl - 1) : 0, ~uint64_t{0} >> (64 - wl), raw_min(), raw_max(),
          overflow == Overflow::kWrap};
}
template <typename Int>
constexpr int64_t FixedFormat::wrap(Int raw) const {
  return raw_overflow().wrap(raw);
}
template <typename Int>
constexpr int64_t FixedFormat::saturate(Int raw) const {
  return raw_overflow().saturate(raw);
}
template <typename Int>
constexpr int64_t FixedFormat::fit(Int raw) const {
  return raw_overflow().fit(raw);
}

// Parse "s4.28", "u1.16:sat", "s4.28:rnd", "u1.16:trn:wrap". A mode not written is sc_fix's
// default: truncate (SC_TRN) and wrap (SC_WRAP). Throws std::invalid_argument naming `what` and
// the text on malformed input.
FixedFormat parse_fixed_format(const std::string& text, const std::string& what);

// Shift helpers that never invoke undefined behaviour for negative values or large shifts.
constexpr Int128 shift_left(Int128 v, int n) { return n >= 0 ? v * (Int128{1} << n) : v; }

// floor(v / 2^n) for 0 <= n < 128: an arithmetic shift (GCC and Clang define >> on negative
// signed values as arithmetic; C++20 requires it), not a 128-bit division.
constexpr Int128 floor_shift_right(Int128 v, int n) { return n <= 0 ? v : (v >> n); }

}  // namespace shadesim
