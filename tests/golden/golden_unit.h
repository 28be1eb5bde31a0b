// An oracle for ShadeUnit written from the documentation, not from the model's code: each pixel
// is evaluated without forward differences (wrapping series: the closed form
// v_k = v_0 + k d_0 + k(k-1)/2 d2 in exact integer arithmetic, reduced once; saturating series:
// the documented per-step rule, since saturation does not commute), then the specular unit and
// the combine are applied straight from their documented formulas (model/*.h header comments),
// every quantization done by SystemC's sc_fix / sc_ufix (IEEE 1666), none by FixedFormat.
// A test oracle, not product code: slow, and shares nothing with model/ but the data types of
// the command stream and the configuration.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/command_stream.h"
#include "model/unit_config.h"

namespace shadesim::golden {

struct Pixel {
  int x = 0, y = 0;
  std::array<int64_t, 3> colour{};
  bool end_of_row = false;
};

// raw * 2^-src_frac, exact, converted to `format` by sc_fix (sc_ufix when unsigned) with the
// format's quantization (SC_TRN / SC_RND) and overflow (SC_WRAP / SC_SAT) modes; returns the
// raw integer of the result (its value times 2^frac_bits).
int64_t sc_quantize(__int128 raw, int src_frac, const FixedFormat& format);
// The same from a double (the ideal unit's pow result).
int64_t sc_quantize(double value, const FixedFormat& format);

// Every pixel the stream's SPANs produce, in stream order. Throws std::invalid_argument on a
// SPAN before any TRIANGLE and MATERIAL.
std::vector<Pixel> shade(const CommandStream& stream);

}  // namespace shadesim::golden
