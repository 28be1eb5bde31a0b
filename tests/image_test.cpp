// PNG round trips through libpng, error heat-map colours at the documented stops, side-by-side
// strips.
#include "host/image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>

namespace shadesim {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() /
          ("shadesim_image_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

Image random_image(int w, int h, int channels, unsigned seed) {
  Image im(w, h, channels);
  std::mt19937 rng(seed);
  for (uint8_t& p : im.pixels) p = static_cast<uint8_t>(rng() & 0xff);
  return im;
}

std::array<int, 3> rgb(const Image& im, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * im.width + x) * im.channels;
  if (im.channels == 1) return {im.pixels[i], im.pixels[i], im.pixels[i]};
  return {im.pixels[i], im.pixels[i + 1], im.pixels[i + 2]};
}

TEST(Png, RoundTripGreyAndRgb) {
  for (int channels : {1, 3}) {
    const Image original = random_image(37, 23, channels, 5 + channels);
    const std::string path = temp_path("rt" + std::to_string(channels) + ".png");
    write_png(path, original);
    const Image back = read_png(path);
    fs::remove(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(back.channels, channels);
    EXPECT_EQ(back.pixels, original.pixels);
  }
}

TEST(Png, WriteIntoMissingDirectoryNamesThePath) {
  const std::string path = temp_path("no_such_dir") + "/out.png";
  try {
    write_png(path, Image(4, 4, 1));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(Png, ReadingGarbageOrMissingFileFails) {
  const std::string path = temp_path("garbage.png");
  std::ofstream(path) << "not a png at all";
  EXPECT_THROW(read_png(path), std::runtime_error);
  fs::remove(path);
  EXPECT_THROW(read_png(temp_path("absent.png")), std::runtime_error);
}

TEST(Png, RejectsInconsistentImage) {
  Image bad(4, 4, 3);
  bad.pixels.resize(10);
  EXPECT_THROW(write_png(temp_path("bad.png"), bad), std::runtime_error);
  EXPECT_THROW(Image(4, 4, 2), std::invalid_argument);
}

TEST(HeatMap, EndpointsAndStops) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> errors = {0.0, 1e-9, 1.0, 2.0, 3.0, 100.0, nan, -3.0};
  const Image im = error_heat_map(errors, 8, 1, 3.0);
  ASSERT_EQ(im.channels, 3);
  using C = std::array<int, 3>;
  EXPECT_EQ(rgb(im, 0, 0), (C{0, 0, 0}));      // exactly zero: black
  EXPECT_EQ(rgb(im, 1, 0), (C{0, 0, 255}));    // just above zero: blue
  EXPECT_EQ(rgb(im, 2, 0), (C{0, 255, 0}));    // a third of full scale: green
  EXPECT_EQ(rgb(im, 3, 0), (C{255, 255, 0}));  // two thirds: yellow
  EXPECT_EQ(rgb(im, 4, 0), (C{255, 0, 0}));    // full scale: red
  EXPECT_EQ(rgb(im, 5, 0), (C{255, 0, 0}));    // beyond: still red
  const C grey = rgb(im, 6, 0);                // not covered: dark grey
  EXPECT_EQ(grey[0], grey[1]);
  EXPECT_EQ(grey[1], grey[2]);
  EXPECT_GT(grey[0], 0);
  EXPECT_LT(grey[0], 96);
  EXPECT_EQ(rgb(im, 7, 0), (C{255, 0, 0}));  // the sign is ignored
}

TEST(HeatMap, RampIsMonotoneInTheHueOrder) {
  // Along blue -> green the blue falls while green rises, and so on; check midpoints by hand.
  const Image im = error_heat_map({0.5, 1.5, 2.5}, 3, 1, 3.0);
  using C = std::array<int, 3>;
  EXPECT_EQ(rgb(im, 0, 0), (C{0, 128, 128}));
  EXPECT_EQ(rgb(im, 1, 0), (C{128, 255, 0}));
  EXPECT_EQ(rgb(im, 2, 0), (C{255, 128, 0}));
  EXPECT_THROW(error_heat_map({1.0}, 2, 1, 1.0), std::invalid_argument);
  EXPECT_THROW(error_heat_map({1.0}, 1, 1, 0.0), std::invalid_argument);
}

TEST(Hstack, PromotesGreyPadsAndSeparates) {
  Image grey(2, 3, 1);
  for (size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = static_cast<uint8_t>(10 + i);
  Image colour(3, 1, 3);
  for (size_t i = 0; i < colour.pixels.size(); ++i)
    colour.pixels[i] = static_cast<uint8_t>(100 + i);
  const Image out = hstack({grey, colour}, 1);
  ASSERT_EQ(out.width, 2 + 1 + 3);
  ASSERT_EQ(out.height, 3);
  ASSERT_EQ(out.channels, 3);
  using C = std::array<int, 3>;
  EXPECT_EQ(rgb(out, 0, 0), (C{10, 10, 10}));
  EXPECT_EQ(rgb(out, 1, 2), (C{15, 15, 15}));
  EXPECT_EQ(rgb(out, 2, 0), (C{128, 128, 128}));  // gap
  EXPECT_EQ(rgb(out, 3, 0), (C{100, 101, 102}));
  EXPECT_EQ(rgb(out, 5, 0), (C{106, 107, 108}));
  EXPECT_EQ(rgb(out, 4, 1), (C{0, 0, 0}));  // below the shorter image
  const Image greys = hstack({grey, grey}, 0);
  EXPECT_EQ(greys.channels, 1);
  EXPECT_EQ(greys.width, 4);
}

}  // namespace
}  // namespace shadesim
