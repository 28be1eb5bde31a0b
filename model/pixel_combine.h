// PixelCombine: ambient + diffuse + specular per channel, clamp, round to the output code.
// Mirrors rtl/pixel_combine.sv.
//
//   stage 1  each diffuse series value clamped below at 0 (sign bit test: max(0, N.L) per light)
//            each specular intensity s_l times the light's specular colour k_lc (a small
//            unsigned multiply), brought to the series fraction bits by the series rule
//            the specular gate of light l: g_l = (sum over channels c of D_lc) > 0 - an adder
//            per extra channel and a comparator per light. Specular is added only where g_l
//            is 1, i.e. where N.L > 0 ("no highlight through the terminator"). The host writes
//            D_lc = kd_c L_c (N.L)/|N| with kd_c L_c >= 0, so the sum is (sum_c kd_c L_c) N.L:
//            a channel of colour 0 adds exactly 0, and the sign's error is the channels'
//            quantization error over the summed scale (a per-channel OR would divide by the
//            smallest non-zero scale instead). When every kd_c L_c of light l is 0 but the
//            light has a specular colour, the host writes channel 0's series unscaled,
//            (N.L)/|N|, and sets bit l of the MATERIAL's gate-only mask: that series then sets
//            g_l and is not added to the colour.
//   stage 2  exact sum per channel: ambient_c + sum_l max(0, D_lc) [not gate-only]
//                                   + sum_l g_l s_l k_lc
//   stage 3  output code = round-to-nearest into u0.out_bits, saturating (negative -> 0,
//            >= 1 - 2^-(out_bits+1) -> all ones). A code c stands for c / 2^out_bits.
// Pipelining (UnitConfig::combine_stages; the clock, not the numbers): 1 registers stage 1's
// terms before stage 2's sum; 2 also registers each colour product as two partial products
// (rtl/split_multiply.sv) before its rounding and gate, and adds each light's diffuse and
// specular term before the terms register. Every sum is exact, so the codes are the same; the
// cycle model (model/cycle_model.h) counts the stages' latency.
// Specular kind none (no specular term): stage 1 has no products and no gates, stage 2 no
// specular sum; spec and spec_colour are not read (pixel_combine.sv's SPECULAR = 0 branch).
// Diffuse colour multiply (UnitConfig::diffuse_colour kMultiply): light l has one diffuse
// series, N_l = (N.L)/|N| itself. Stage 1 forms max(0, N_l) x kd_lc per channel, brought to the
// series fraction bits by the series rule like the specular product (kd_lc = kd_c L_c in the
// spec_colour format, from the MATERIAL), and the gate is g_l = N_l > 0; stage 2 adds these
// products in place of max(0, D_lc). There is no gate-only light: N_l always gates. The
// multiplier takes N_l truncated to the colour's fraction bits (where the series has more):
// only those reach an output code (an error below 2^-F_colour x kd), and the multiply is
// about colour-sized instead of series-sized - the six of an RGB two-light unit would be
// most of its area at full width.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "model/unit_config.h"

namespace shadesim {

constexpr int kMaxChannels = 3;
constexpr int kMaxLights = 8;  // UnitConfig::validate's bound

class PixelCombine {
 public:
  explicit PixelCombine(const UnitConfig& c)
      : channels_(c.channels),
        lights_(c.lights),
        specular_(c.specular.kind != SpecularUnitKind::kNone),
        series_(c.series),
        multiply_(c.diffuse_multiply()),
        product_frac_(c.specular.out.frac_bits() + c.spec_colour.frac_bits()),
        nl_operand_(nl_operand_format(c)),
        diffuse_frac_(nl_operand_.frac_bits() + c.spec_colour.frac_bits()),
        out_(output_format(c.out_bits)) {}

  // The output code's format: u0.out_bits, round to nearest, saturating. The reference's codes
  // (host/metrics.cpp) use it too.
  static constexpr FixedFormat output_format(int out_bits) {
    return {out_bits, 0, false, Quantization::kRoundNearest, Overflow::kSaturate};
  }

  // The specular gate of light l (stage 1): the sum of its channels' diffuse values is > 0 (with
  // the diffuse colour multiply: its one series is > 0).
  bool gate(const int64_t* diffuse, int l) const {
    if (multiply_) return diffuse[l] > 0;
    Int128 sum = 0;
    for (int c = 0; c < channels_; ++c) sum += diffuse[l * channels_ + c];
    return sum > 0;
  }

  // diffuse[l * channels + c] (with the multiply diffuse[l]), spec[l], ambient[c],
  // spec_colour[l * channels + c], diffuse_colour[l * channels + c] (read with the multiply
  // only); gate_only: the MATERIAL's mask (bit l: light l's diffuse series gate only, not added).
  std::array<uint16_t, kMaxChannels> operator()(const int64_t* diffuse, const int64_t* spec,
                                                const int64_t* ambient, const int64_t* spec_colour,
                                                const int64_t* diffuse_colour,
                                                uint32_t gate_only) const {
    std::array<bool, kMaxLights> lit{};
    for (int l = 0; specular_ && l < lights_; ++l) lit[static_cast<size_t>(l)] = gate(diffuse, l);
    std::array<uint16_t, kMaxChannels> out{};
    for (int c = 0; c < channels_; ++c) {
      Int128 acc = ambient[c];
      for (int l = 0; l < lights_; ++l) {
        acc += diffuse_term(diffuse, diffuse_colour, gate_only, l, c);
        if (!lit[static_cast<size_t>(l)]) continue;
        const Int128 product = Int128{spec[l]} * spec_colour[l * channels_ + c];
        acc += series_.quantize(product, product_frac_);
      }
      out[c] = static_cast<uint16_t>(out_.quantize(acc, series_.frac_bits()));
    }
    return out;
  }

 private:
  // N_l truncated to the colour's fraction bits (all of the series' where it has fewer), with the
  // series' integer bits.
  static FixedFormat nl_operand_format(const UnitConfig& c) {
    const int frac = std::min(c.series.frac_bits(), c.spec_colour.frac_bits());
    return {c.series.iwl + frac, c.series.iwl, true, Quantization::kTruncate, Overflow::kWrap};
  }

  // Stage 1's diffuse value of light l in channel c: max(0, D_lc) unless gate-only, or with the
  // multiply max(0, N_l) (to the colour's fraction bits) x kd_lc by the series rule.
  Int128 diffuse_term(const int64_t* diffuse, const int64_t* diffuse_colour, uint32_t gate_only,
                      int l, int c) const {
    if (multiply_) {
      const int64_t n = diffuse[l];
      if (n <= 0) return 0;
      const int64_t operand = nl_operand_.quantize(n, series_.frac_bits());
      return series_.quantize(Int128{operand} * diffuse_colour[l * channels_ + c], diffuse_frac_);
    }
    const int64_t d = diffuse[l * channels_ + c];
    return (gate_only >> l & 1) == 0 && d > 0 ? d : 0;
  }

  int channels_;
  int lights_;
  bool specular_;  // false for specular kind none: no specular term at all
  FixedFormat series_;
  bool multiply_;  // UnitConfig::diffuse_colour kMultiply
  int product_frac_;
  FixedFormat nl_operand_;  // N_l as the multiplier takes it
  int diffuse_frac_;        // fraction bits of N_l x kd_lc
  FixedFormat out_;
};

}  // namespace shadesim
