#include "host/image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace shadesim {

Image::Image(int w, int h, int c) : width(w), height(h), channels(c) {
  if (w < 0 || h < 0 || (c != 1 && c != 3)) {
    throw std::invalid_argument("Image: expected width, height >= 0 and 1 or 3 channels, got " +
                                std::to_string(w) + "x" + std::to_string(h) + "x" +
                                std::to_string(c));
  }
  pixels.assign(static_cast<size_t>(w) * h * c, 0);
}

void write_png(const std::string& path, const Image& image) {
  if ((image.channels != 1 && image.channels != 3) || image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * image.channels) {
    throw std::runtime_error(path +
                             ": cannot write PNG: image is not a non-empty 1- or 3-channel "
                             "image whose pixel count matches its size");
  }
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = image.channels == 1 ? PNG_FORMAT_GRAY : PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&png, path.c_str(), 0, image.pixels.data(), 0, nullptr)) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw std::runtime_error(path + ": cannot write PNG: " + reason +
                             " (does the directory exist and is it writable?)");
  }
}

Image read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    throw std::runtime_error(path + ": cannot read PNG: " + std::string(png.message));
  }
  const bool colour = (png.format & PNG_FORMAT_FLAG_COLOR) != 0;
  png.format = colour ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;
  Image image(static_cast<int>(png.width), static_cast<int>(png.height), colour ? 3 : 1);
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw std::runtime_error(path + ": cannot read PNG: " + reason);
  }
  return image;
}

Image error_heat_map(const std::vector<double>& error_lsb, int width, int height,
                     double full_scale_lsb) {
  if (error_lsb.size() != static_cast<size_t>(width) * height || !(full_scale_lsb > 0)) {
    throw std::invalid_argument("error_heat_map: expected width*height errors and full scale > 0");
  }
  // Colour stops at t = 0, 1/3, 2/3, 1 of full scale; t = 0 itself is black.
  static const double kStops[4][3] = {{0, 0, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
  Image image(width, height, 3);
  for (size_t i = 0; i < error_lsb.size(); ++i) {
    uint8_t* p = &image.pixels[3 * i];
    const double e = std::fabs(error_lsb[i]);
    if (std::isnan(e)) {
      p[0] = p[1] = p[2] = 48;
      continue;
    }
    if (e == 0) continue;  // black
    const double t = std::min(e / full_scale_lsb, 1.0) * 3.0;
    const int k = std::min(static_cast<int>(t), 2);
    const double f = t - k;
    for (int c = 0; c < 3; ++c) {
      p[c] =
          static_cast<uint8_t>(std::lround(kStops[k][c] + f * (kStops[k + 1][c] - kStops[k][c])));
    }
  }
  return image;
}

Image hstack(const std::vector<Image>& images, int gap) {
  if (images.empty()) throw std::invalid_argument("hstack: expected at least one image");
  if (gap < 0) throw std::invalid_argument("hstack: expected gap >= 0");
  int width = gap * static_cast<int>(images.size() - 1), height = 0, channels = 1;
  for (const Image& im : images) {
    width += im.width;
    height = std::max(height, im.height);
    channels = std::max(channels, im.channels);
  }
  Image out(width, height, channels);
  std::fill(out.pixels.begin(), out.pixels.end(), uint8_t{128});
  int x0 = 0;
  for (const Image& im : images) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < im.width; ++x) {
        uint8_t* dst = &out.pixels[(static_cast<size_t>(y) * width + x0 + x) * channels];
        for (int c = 0; c < channels; ++c) {
          if (y >= im.height) {
            dst[c] = 0;
          } else {
            const size_t src = (static_cast<size_t>(y) * im.width + x) * im.channels;
            dst[c] = im.pixels[src + (im.channels == 1 ? 0 : c)];
          }
        }
      }
    }
    x0 += im.width + gap;
  }
  return out;
}

}  // namespace shadesim
