// How a TRIANGLE's coefficients fill its payload words: the one C++ definition (the RTL's twin
// is shade_pkg::coef_word / coef_lsb).
//
// The coefficients go in stream order (series by series, T0..T5 within a series), each taking
// coef_term_bits(t) bits, two's complement. Each starts at the lowest bit of the current word
// that is still free; one that does not fit in what is left of the word starts the next word.
// A coefficient never straddles two words, so the unit takes each from one word with a fixed
// shift. With every term in a 36-bit coef format (the default) that is one coefficient per word;
// s2.15 terms go three to a word.
#pragma once

#include <cstdint>
#include <vector>

#include "model/fixed_point.h"
#include "model/unit_config.h"

namespace shadesim {

struct CoefSlot {
  int word = 0;  // payload word (0 = the first after the TRIANGLE header)
  int lsb = 0;   // lowest bit in that word
  int bits = 0;  // width: the term's format's wl
};

struct CoefLayout {
  std::vector<CoefSlot> slots;  // one per coefficient, in stream order
  int words = 0;                // payload words of a TRIANGLE

  static CoefLayout of(const UnitConfig& config) {
    CoefLayout layout;
    constexpr int kWordBits = 64;
    const int terms = 6;
    int word = 0, lsb = 0;
    for (int i = 0; i < config.series_per_triangle() * terms; ++i) {
      const int bits = config.coef_term_bits(i % terms);
      if (lsb + bits > kWordBits) {
        ++word;
        lsb = 0;
      }
      layout.slots.push_back({word, lsb, bits});
      lsb += bits;
    }
    layout.words = layout.slots.empty() ? 0 : word + 1;
    return layout;
  }

  // Raw coefficients (each fits its term's format) -> payload words.
  std::vector<uint64_t> pack(const std::vector<int64_t>& coef) const {
    std::vector<uint64_t> out(static_cast<size_t>(words), 0);
    for (size_t i = 0; i < slots.size() && i < coef.size(); ++i) {
      const CoefSlot& s = slots[i];
      out[static_cast<size_t>(s.word)] |= (static_cast<uint64_t>(coef[i]) & mask(s.bits)) << s.lsb;
    }
    return out;
  }

  // Payload words -> raw coefficients, each sign-extended from its width (the wrap of a signed
  // format of that word length: the field's two's-complement bits read as a number).
  std::vector<int64_t> unpack(const uint64_t* payload) const {
    std::vector<int64_t> out;
    out.reserve(slots.size());
    for (const CoefSlot& s : slots) {
      const FixedFormat field_format{s.bits, s.bits, true, Quantization::kTruncate,
                                     Overflow::kWrap};
      out.push_back(field_format.wrap(payload[s.word] >> s.lsb));
    }
    return out;
  }

 private:
  static uint64_t mask(int bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }
};

}  // namespace shadesim
