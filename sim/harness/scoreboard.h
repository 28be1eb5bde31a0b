// Scoreboard: compares the RTL's pixel stream with the bit-accurate model's (every field of every
// pixel) and each scanline's completion cycle with the cycle model's. Backend-neutral: the
// Verilator C++ loop and the SystemC sink feed it the same events. Stops at the first mismatch
// and describes it.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "model/shade_unit.h"
#include "model/cycle_model.h"

namespace shadesim {

struct Mismatch {
  enum class Kind { kNone, kPixel, kCycle, kExtraPixel, kTimeout };
  Kind kind = Kind::kNone;
  int scanline = -1;  // index of the scanline (count of end-of-row pixels before it)
  int y = -1, x = -1;
  std::string expected, got;
  uint64_t cycle = 0;
};

std::string to_string(Mismatch::Kind kind);

class Scoreboard {
 public:
  Scoreboard(std::vector<PixelOut> expected, int channels);

  // A pixel left the RTL on `cycle`.
  void rtl_pixel(const PixelOut& got, uint64_t cycle);
  // The cycle model's end-of-row pixel left on `cycle`.
  void model_scanline(const ScanlineDone& done);
  // The run stopped at `cycle` without finishing.
  void timeout(uint64_t cycle);

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
  void fail(Mismatch m);
  void compare_rows();
  std::string describe(const PixelOut& p) const;

  std::vector<PixelOut> expected_;
  int channels_;
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
