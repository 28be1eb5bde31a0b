// How a SPAN's start values fill its payload words with host span setup
// (UnitConfig::span_setup == kHost): the one C++ definition (the RTL's twin is
// shade_pkg::start_words; rtl/start_bank.sv reads the fields).
//
// The values go in stream order, series by series (diffuse l-major/c-minor, then specular per
// light), v, d, d2 within a series, each SERIES_WL bits two's complement, packed densely: value j
// occupies bits [j*wl, (j+1)*wl) of the payload read as one little-endian bit string (word 0
// holds bits 0..63). A value may straddle two words: the unit keeps the payload words as they
// came and reads each value with a fixed shift, so straddling costs it nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "model/fixed_point.h"
#include "model/unit_config.h"

namespace shadesim {

struct StartLayout {
  static constexpr int kValuesPerSeries = 3;  // v, d, d2
  static constexpr int kWordBits = 64;
  int values = 0;      // 3 x series_per_triangle
  int value_bits = 0;  // the series format's wl
  int words = 0;       // payload words of a SPAN

  static StartLayout of(const UnitConfig& config) {
    StartLayout l;
    l.values = kValuesPerSeries * config.series_per_triangle();
    l.value_bits = config.series.wl;
    l.words = (l.values * l.value_bits + kWordBits - 1) / kWordBits;
    return l;
  }

  // Raw series-format values (each fits value_bits as two's complement) -> payload words.
  std::vector<uint64_t> pack(const std::vector<int64_t>& v) const {
    std::vector<uint64_t> out(static_cast<size_t>(words), 0);
    for (size_t j = 0; j < v.size() && j < static_cast<size_t>(values); ++j) {
      const uint64_t bits = static_cast<uint64_t>(v[j]) & mask(value_bits);
      const int at = static_cast<int>(j) * value_bits;
      const auto word = static_cast<size_t>(at / kWordBits);
      const int lsb = at % kWordBits;
      out[word] |= bits << lsb;
      if (lsb + value_bits > kWordBits) out[word + 1] |= bits >> (kWordBits - lsb);
    }
    return out;
  }

  // Payload words -> raw values, each sign-extended from value_bits.
  std::vector<int64_t> unpack(const uint64_t* payload) const {
    const FixedFormat field{value_bits, value_bits, true, Quantization::kTruncate, Overflow::kWrap};
    std::vector<int64_t> out;
    out.reserve(static_cast<size_t>(values));
    for (int j = 0; j < values; ++j) {
      const int at = j * value_bits;
      const auto word = static_cast<size_t>(at / kWordBits);
      const int lsb = at % kWordBits;
      uint64_t bits = payload[word] >> lsb;
      if (lsb + value_bits > kWordBits) bits |= payload[word + 1] << (kWordBits - lsb);
      out.push_back(field.wrap(bits & mask(value_bits)));
    }
    return out;
  }

 private:
  static uint64_t mask(int bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }
};

}  // namespace shadesim
