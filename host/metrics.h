// Error of the model's output codes against the double-precision reference, in output LSBs.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/shade_unit.h"

namespace shadesim {

struct ErrorStats {
  std::size_t pixels = 0;  // pixels compared (owned by a triangle)
  // |model code - reference code|, the reference rounded by the unit's own output rule
  // (code = clamp(floor(r * 2^bits + 1/2), 0, 2^bits - 1)): what two 8-bit images show.
  int max_code_lsb = 0;
  double mean_code_lsb = 0;
  double psnr_db = 0;  // over compared pixels, from the code differences; +inf if equal
  // |model code - r * 2^bits| before rounding the reference: includes the output rounding.
  double max_real_lsb = 0;
  std::size_t pixels_over_1lsb = 0;  // pixels whose code differs by more than 1 in any channel
  // The code figures per channel (entries past the unit's channels stay 0).
  std::array<int, kMaxChannels> max_code_lsb_channel{};
  std::array<double, kMaxChannels> mean_code_lsb_channel{};
};

struct ErrorMap {
  ErrorStats stats;
  std::vector<double>
      per_pixel_lsb;  // width*height, max over channels of the real error; NaN where empty
};

// reference: width*height*channels values in [0,1]; owner: width*height (-1 empty);
// pixels: the model's output stream.
ErrorMap compare_to_reference(const std::vector<PixelOut>& pixels,
                              const std::vector<double>& reference,
                              const std::vector<int32_t>& owner, int width, int height,
                              int channels, int out_bits);

// The reference rounded to output codes, for writing as an image.
std::vector<uint8_t> reference_codes(const std::vector<double>& reference, int out_bits);

}  // namespace shadesim
