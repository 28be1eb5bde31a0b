#include "host/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "model/pixel_combine.h"

namespace shadesim {
namespace {

// The reference's output code: the unit's own output rule (PixelCombine::output_format).
double code_of(double r, int out_bits) {
  return static_cast<double>(PixelCombine::output_format(out_bits).from_double(r));
}

}  // namespace

ErrorMap compare_to_reference(const std::vector<PixelOut>& pixels,
                              const std::vector<double>& reference,
                              const std::vector<int32_t>& owner, int width, int height,
                              int channels, int out_bits) {
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (reference.size() != n * static_cast<size_t>(channels) || owner.size() != n) {
    throw std::invalid_argument("compare_to_reference: buffer sizes do not match the image");
  }
  ErrorMap map;
  map.per_pixel_lsb.assign(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<uint8_t> seen(n, 0);
  double sum_abs = 0, sum_sq = 0;
  std::array<double, kMaxChannels> sum_abs_channel{};
  const double scale = std::ldexp(1.0, out_bits);
  for (const auto& p : pixels) {
    if (p.x >= width || p.y >= height)
      throw std::runtime_error("model emitted a pixel outside the image");
    const size_t idx = static_cast<size_t>(p.y) * static_cast<size_t>(width) + p.x;
    if (seen[idx]++)
      throw std::runtime_error("model shaded pixel (" + std::to_string(p.x) + ", " +
                               std::to_string(p.y) + ") twice");
    double worst_real = 0;
    int worst_code = 0;
    for (int c = 0; c < channels; ++c) {
      const double r = reference[idx * static_cast<size_t>(channels) + static_cast<size_t>(c)];
      const int diff = std::abs(static_cast<int>(p.colour[static_cast<size_t>(c)]) -
                                static_cast<int>(code_of(r, out_bits)));
      worst_code = std::max(worst_code, diff);
      map.stats.max_code_lsb_channel[static_cast<size_t>(c)] =
          std::max(map.stats.max_code_lsb_channel[static_cast<size_t>(c)], diff);
      sum_abs_channel[static_cast<size_t>(c)] += diff;
      worst_real = std::max(worst_real, std::fabs(p.colour[static_cast<size_t>(c)] -
                                                  std::min(r * scale, scale - 1.0)));
      sum_abs += diff;
      sum_sq += static_cast<double>(diff) * diff;
    }
    map.per_pixel_lsb[idx] = worst_real;
    map.stats.max_code_lsb = std::max(map.stats.max_code_lsb, worst_code);
    map.stats.max_real_lsb = std::max(map.stats.max_real_lsb, worst_real);
    if (worst_code > 1) ++map.stats.pixels_over_1lsb;
    ++map.stats.pixels;
  }
  for (size_t i = 0; i < n; ++i) {
    if ((owner[i] >= 0) != (seen[i] != 0)) {
      throw std::runtime_error("model and visibility disagree on pixel (" +
                               std::to_string(i % static_cast<size_t>(width)) + ", " +
                               std::to_string(i / static_cast<size_t>(width)) + ")");
    }
  }
  const double samples = static_cast<double>(map.stats.pixels) * channels;
  if (samples > 0) {
    map.stats.mean_code_lsb = sum_abs / samples;
    for (int c = 0; c < channels; ++c) {
      map.stats.mean_code_lsb_channel[static_cast<size_t>(c)] =
          sum_abs_channel[static_cast<size_t>(c)] / static_cast<double>(map.stats.pixels);
    }
    const double mse = sum_sq / samples;
    const double peak = scale - 1.0;
    map.stats.psnr_db =
        mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
  }
  return map;
}

std::vector<uint8_t> reference_codes(const std::vector<double>& reference, int out_bits) {
  std::vector<uint8_t> out(reference.size());
  const int shift = out_bits > 8 ? out_bits - 8 : 0;
  for (size_t i = 0; i < reference.size(); ++i) {
    out[i] = static_cast<uint8_t>(static_cast<int>(code_of(reference[i], out_bits)) >> shift);
  }
  return out;
}

}  // namespace shadesim
