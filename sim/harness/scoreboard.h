// Scoreboard: compares the RTL's pixel stream with the bit-accurate model's (every field of every
// pixel) and each scanline's completion cycle with the cycle model's. Backend-neutral: the
// Verilator C++ loop and the SystemC sink feed it the same events. Stops at the first mismatch
// and describes it.
//
// With pixel lanes the RTL's pixels leave in beats; the backends hand them over one pixel at a
// time in lane order (score_beat in cosim.h), each with its lane, and the lane is compared like
// every other field: a beat that ends early, runs into the next span or has a hole in its mask
// puts a pixel on a lane the model did not expect (PixelOut::lane).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "model/shade_unit.h"
#include "model/cycle_model.h"

namespace shadesim {

struct Mismatch {
  enum class Kind { kNone, kPixel, kCycle, kExtraPixel, kTimeout, kHang };
  Kind kind = Kind::kNone;
  int scanline = -1;  // index of the scanline (count of end-of-row pixels before it)
  int y = -1, x = -1;
  std::string expected, got;
  uint64_t cycle = 0;
};

std::string to_string(Mismatch::Kind kind);

class Scoreboard {
 public:
  Scoreboard(std::vector<PixelOut> expected, int channels, int lanes = 1);

  // The common case of a pixel leaving the RTL on `cycle`, straight from the pix_* ports (channel
  // c of `colour` in bits [c*out_bits +: out_bits], as unpack_pixel reads them): when it is the
  // expected pixel and does not end a row, counts it and returns true. Otherwise changes nothing
  // and returns false; the caller then passes the unpacked pixel to rtl_pixel(). Saves building
  // a PixelOut on every cycle.
  bool rtl_pixel_if_expected(uint64_t x, uint64_t y, uint64_t colour, bool eor, int out_bits,
                             uint64_t cycle, int lane = 0) {
    if (failed() || next_ >= expected_.size()) return false;
    const PixelOut& want = expected_[next_];
    if (want.end_of_row || eor || want.x != static_cast<uint16_t>(x) || want.y != static_cast<uint16_t>(y) ||
        want.lane != lane) {
      return false;
    }
    const uint64_t mask = (uint64_t{1} << out_bits) - 1;
    for (int c = 0; c < channels_; ++c) {
      if (want.colour[c] != static_cast<uint16_t>((colour >> (c * out_bits)) & mask)) return false;
    }
    ++next_;
    cycles_ = cycle + 1;
    return true;
  }
  // A pixel left the RTL on `cycle`. Inline for the common case (the expected pixel, not the
  // end of a row): it runs on nearly every simulated cycle.
  void rtl_pixel(const PixelOut& got, uint64_t cycle) {
    if (!failed() && next_ < expected_.size()) {
      const PixelOut& want = expected_[next_];
      if (!want.end_of_row && same_pixel(want, got)) {
        ++next_;
        cycles_ = cycle + 1;
        return;
      }
    }
    rtl_pixel_checked(got, cycle);
  }
  // The cycle model's end-of-row pixel left on `cycle`.
  void model_scanline(const ScanlineDone& done);
  // A beat left the RTL on `cycle` with a lane mask that is not lanes 0 .. n-1 (n >= 1).
  void rtl_bad_mask(uint64_t x, uint64_t y, uint64_t mask, uint64_t cycle);
  // The run stopped at `cycle` without finishing.
  void timeout(uint64_t cycle);
  // The watchdog (sim/harness/watchdog.h) fired on `cycle`: no pix_valid_o since `quiet_since`,
  // more than `limit` cycles, with pixels still expected.
  void hang(uint64_t cycle, uint64_t quiet_since, uint64_t limit);
  // Some expected pixel has not left the RTL yet.
  bool pixels_pending() const { return next_ < expected_.size(); }

  bool failed() const { return first_.kind != Mismatch::Kind::kNone; }
  // Every expected pixel seen and every scanline's cycle compared.
  bool complete() const {
    return next_ == expected_.size() && rtl_rows_.empty() && model_rows_.empty() &&
           rows_compared_ == expected_rows_;
  }
  const Mismatch& first_mismatch() const { return first_; }
  uint64_t pixels_checked() const { return next_; }
  uint64_t scanlines_checked() const { return rows_compared_; }
  const std::vector<ScanlineDone>& rtl_scanlines() const { return rtl_done_; }
  // Cycles until the last pixel left (its cycle + 1); 0 before any pixel.
  uint64_t cycles() const { return cycles_; }

 private:
  // Every field the RTL drives: x, y, end of row and the configured channels.
  bool same_pixel(const PixelOut& want, const PixelOut& got) const {
    if (want.x != got.x || want.y != got.y || want.end_of_row != got.end_of_row || want.lane != got.lane) {
      return false;
    }
    for (int c = 0; c < channels_; ++c) {
      if (want.colour[c] != got.colour[c]) return false;
    }
    return true;
  }
  // Everything else: ends of rows, mismatches, pixels after a failure or past the end.
  void rtl_pixel_checked(const PixelOut& got, uint64_t cycle);
  void fail(Mismatch m);
  void compare_rows();
  std::string describe(const PixelOut& p) const;

  std::vector<PixelOut> expected_;
  int channels_;
  int lanes_;
  size_t next_ = 0;
  int scanline_ = 0;  // scanline of expected_[next_]
  uint64_t expected_rows_ = 0;
  uint64_t rows_compared_ = 0;
  std::deque<ScanlineDone> rtl_rows_, model_rows_;
  std::vector<ScanlineDone> rtl_done_;
  Mismatch first_;
  uint64_t cycles_ = 0;
};

}  // namespace shadesim
