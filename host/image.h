// 8-bit images, PNG files, error heat maps and side-by-side strips.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace shadesim {

struct Image {
  int width = 0, height = 0;
  int channels = 1;             // 1 (grey) or 3 (RGB)
  std::vector<uint8_t> pixels;  // row-major, top row first, channels interleaved

  Image() = default;
  Image(int width, int height, int channels);  // zero-filled; throws std::invalid_argument
};

// Throws std::runtime_error naming the path on failure (e.g. a missing directory).
void write_png(const std::string& path, const Image& image);
// Reads an 8-bit grey or RGB view of any PNG (alpha dropped, palette expanded).
Image read_png(const std::string& path);

// RGB heat map of |error| in LSBs: exactly 0 is black; above that the colour runs blue -> green ->
// yellow -> red, reaching red at full_scale_lsb and staying red beyond. NaN (pixel not covered) is
// dark grey. error_lsb has width*height entries, row-major.
Image error_heat_map(const std::vector<double>& error_lsb, int width, int height,
                     double full_scale_lsb);

// The images left to right, top-aligned, separated by `gap` columns of mid grey; shorter images are
// padded with black below. Grey images are promoted to RGB when any image is RGB.
Image hstack(const std::vector<Image>& images, int gap);

}  // namespace shadesim
