// PixelCombine: ambient + diffuse + specular per channel, clamp, round to the output code.
// Mirrors rtl/pixel_combine.sv.
//
//   stage 1  each diffuse series value clamped below at 0 (sign bit test: max(0, N.L) per light)
//            each specular intensity s_l times the light's specular colour k_lc (a small
//            unsigned multiply), brought to the series fraction bits by the series rule
//   stage 2  exact sum per channel: ambient_c + sum_l max(0, D_lc) + sum_l s_l k_lc
//   stage 3  output code = round-to-nearest into u0.out_bits, saturating (negative -> 0,
//            >= 1 - 2^-(out_bits+1) -> all ones). A code c stands for c / 2^out_bits.
#pragma once

#include <array>
#include <cstdint>

#include "model/unit_config.h"

namespace shadesim {

constexpr int kMaxChannels = 3;

class PixelCombine {
 public:
  explicit PixelCombine(const UnitConfig& c)
      : channels_(c.channels),
        lights_(c.lights),
        series_(c.series),
        product_frac_(c.specular.out.frac_bits() + c.spec_colour.frac_bits()),
        out_(output_format(c.out_bits)) {}

  // The output code's format: u0.out_bits, round to nearest, saturating. The reference's codes
  // (host/metrics.cpp) use it too.
  static constexpr FixedFormat output_format(int out_bits) {
    return {out_bits, 0, false, Quantization::kRoundNearest, Overflow::kSaturate};
  }

  // diffuse[l * channels + c], spec[l], ambient[c], spec_colour[l * channels + c].
  std::array<uint16_t, kMaxChannels> operator()(const int64_t* diffuse, const int64_t* spec,
                                                const int64_t* ambient,
                                                const int64_t* spec_colour) const {
    std::array<uint16_t, kMaxChannels> out{};
    for (int c = 0; c < channels_; ++c) {
      Int128 acc = ambient[c];
      for (int l = 0; l < lights_; ++l) {
        const int64_t d = diffuse[l * channels_ + c];
        acc += d > 0 ? d : 0;
        const Int128 product = Int128{spec[l]} * spec_colour[l * channels_ + c];
        acc += series_.quantize(product, product_frac_);
      }
      out[c] = static_cast<uint16_t>(out_.quantize(acc, series_.frac_bits()));
    }
    return out;
  }

 private:
  int channels_;
  int lights_;
  FixedFormat series_;
  int product_frac_;
  FixedFormat out_;
};

}  // namespace shadesim
