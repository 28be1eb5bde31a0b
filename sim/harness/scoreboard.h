// Scoreboard: compares what left the RTL with what the two reference models say (the contract
// is in sim/harness/cosim.h):
//   - every field of every pixel with the bit-accurate model's (ShadeUnit::run),
//   - every pixel's exit cycle with the cycle model's (the cycle its beat left the unit),
//   - cmd_ready_o with the cycle model's on every cycle,
//   - and that nothing leaves after the last expected pixel.
// Backend-neutral and free of Verilator: the lockstep block (cosim.h) feeds it observations,
// and so can a unit test. Keeps the first mismatch, with its context, and ignores what follows.
//
// A ready mismatch does not stop the run: a stall downstream (engines, slot) reaches the command
// port as back-pressure a cycle or more before the late pixel leaves, so the pixel side usually
// says more about the cause. The run goes on, each side's driver following its own cmd_ready,
// and the pixel, cycle, extra-pixel or hang mismatch that follows is the one reported, with the
// ready mismatch as its `before`; a ready mismatch nothing follows from is reported on its own
// at the end. Either way the run fails.
//
// Exit cycles are paired in stream order: the RTL's k-th pixel with the cycle model's k-th,
// whichever is seen first waiting for the other, so an RTL that stops altogether is left to the
// watchdog (a hang) rather than reported as late.
//
// With pixel lanes the RTL's pixels leave in beats; the backends hand them over one pixel at a
// time in lane order (score_beat in cosim.h), each with its lane, and the lane is compared like
// every other field: a beat that ends early, runs into the next span or has a hole in its mask
// puts a pixel on a lane the model did not expect (PixelOut::lane).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/shade_unit.h"

namespace shadesim {

struct Mismatch {
  // pixel        a pixel's x, y, end of row, lane or a colour channel differs from ShadeUnit's
  // cycle        a pixel left on another cycle than the cycle model's
  // ready        cmd_ready_o differs from the cycle model's on some cycle
  // extra-pixel  a pixel after the last expected one (pix_valid_o while draining included)
  // timeout      the run reached its cycle bound unfinished
  // hang         no pix_valid_o for longer than the watchdog allows, pixels still expected
  enum class Kind { kNone, kPixel, kCycle, kReady, kExtraPixel, kTimeout, kHang };
  Kind kind = Kind::kNone;
  int scanline = -1;  // index of the scanline (count of end-of-row pixels before it)
  int y = -1, x = -1;
  std::string expected, got;
  uint64_t cycle = 0;
  std::string before;  // an earlier ready mismatch this one follows from (see Scoreboard), or ""
};

std::string to_string(Mismatch::Kind kind);

// The command port on one cycle, for the context of a ready mismatch.
struct CommandPortState {
  bool valid = false;
  size_t beat = 0;     // index of the beat on the port (beats accepted so far)
  size_t beats = 0;    // beats in the stream
  uint64_t word0 = 0;  // word 0 of what is on cmd_data_i
};

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
    if (want.end_of_row || eor || want.x != static_cast<uint16_t>(x) ||
        want.y != static_cast<uint16_t>(y) || want.lane != lane) {
      return false;
    }
    const uint64_t mask = (uint64_t{1} << out_bits) - 1;
    for (int c = 0; c < channels_; ++c) {
      if (want.colour[c] != static_cast<uint16_t>((colour >> (c * out_bits)) & mask)) return false;
    }
    accept_rtl_pixel(cycle);
    return true;
  }
  // The common case of a cycle in step: one pixel (lane 0 of a beat) left the cycle model at
  // (mx, my, meor) and one the RTL with (rx, ry, colour, reor), both on `cycle`, and nothing is
  // waiting for a partner. When both are the bit-accurate model's next pixel, counts it as
  // model_beat() and then rtl_pixel_if_expected() / rtl_pixel() would (their exit cycles are
  // equal) and returns true. Otherwise changes nothing and returns false: the caller then
  // takes those two, which report whatever differs.
  bool pixel_pair_if_expected(uint64_t cycle, int mx, int my, bool meor, uint64_t rx, uint64_t ry,
                              uint64_t colour, bool reor, int out_bits) {
    if (failed() || next_ != model_next_ || next_ >= expected_.size() || !rtl_exit_.empty() ||
        !model_exit_.empty()) {
      return false;
    }
    const PixelOut& want = expected_[next_];
    if (want.lane != 0 || want.x != mx || want.y != my || want.end_of_row != meor ||
        want.x != static_cast<uint16_t>(rx) || want.y != static_cast<uint16_t>(ry) ||
        want.end_of_row != reor) {
      return false;
    }
    const uint64_t mask = (uint64_t{1} << out_bits) - 1;
    for (int c = 0; c < channels_; ++c) {
      if (want.colour[c] != static_cast<uint16_t>((colour >> (c * out_bits)) & mask)) return false;
    }
    ++next_;
    ++model_next_;
    cycles_ = cycle + 1;
    if (want.end_of_row) {
      ++scanline_;
      ++rows_compared_;
    }
    return true;
  }
  // A pixel left the RTL on `cycle`.
  void rtl_pixel(const PixelOut& got, uint64_t cycle) {
    if (!failed() && next_ < expected_.size()) {
      const PixelOut& want = expected_[next_];
      if (!want.end_of_row && same_pixel(want, got)) {
        accept_rtl_pixel(cycle);
        return;
      }
    }
    rtl_pixel_checked(got, cycle);
  }
  // A beat left the cycle model on `cycle`: `count` pixels from x on row y (lanes 0..count-1),
  // `eor` when its last pixel ends a row. Its pixels must be the bit-accurate model's next ones.
  void model_beat(uint64_t cycle, int x, int y, int count, bool eor) {
    if (failed()) return;
    for (int j = 0; j < count; ++j) {
      const size_t k = model_next_;
      if (k >= expected_.size() || expected_[k].x != x + j || expected_[k].y != y ||
          expected_[k].lane != j || expected_[k].end_of_row != (eor && j == count - 1)) {
        model_disagrees(cycle, x + j, y, j, eor && j == count - 1);
        return;
      }
      ++model_next_;
      if (rtl_exit_.empty()) {
        model_exit_.push(cycle);
      } else {
        compare_exit(k, rtl_exit_.pop(), cycle);
        if (failed()) return;
      }
    }
  }
  // cmd_ready_o on `cycle`: the RTL's and the cycle model's, with the same inputs.
  void cmd_ready(uint64_t cycle, bool rtl, bool model, const CommandPortState& port) {
    if (rtl != model && !failed() && ready_.kind == Mismatch::Kind::kNone) {
      ready_mismatch(cycle, rtl, model, port);
    }
  }
  // A beat left the RTL on `cycle` with a lane mask that is not lanes 0 .. n-1 (n >= 1).
  void rtl_bad_mask(uint64_t x, uint64_t y, uint64_t mask, uint64_t cycle);
  // pix_valid_o on `cycle` after the run was complete (while draining the pipeline), whether or
  // not pix_ready_i took it: a pixel nobody expects.
  void rtl_valid_after_end(uint64_t x, uint64_t y, uint64_t mask, uint64_t cycle);
  // The run stopped at `cycle` without finishing.
  void timeout(uint64_t cycle);
  // The watchdog (sim/harness/watchdog.h) fired on `cycle`: no pix_valid_o since `quiet_since`,
  // more than `limit` cycles, with pixels still expected.
  void hang(uint64_t cycle, uint64_t quiet_since, uint64_t limit);
  // Some expected pixel has not left the RTL yet.
  bool pixels_pending() const { return next_ < expected_.size(); }

  // A mismatch on the pixel side (or a hang or timeout): the run can stop.
  bool failed() const { return first_.kind != Mismatch::Kind::kNone; }
  // No mismatch of any kind, ready included.
  bool passed() const { return !failed() && ready_.kind == Mismatch::Kind::kNone; }
  // Every expected pixel left both the RTL and the cycle model, and every exit cycle compared.
  bool complete() const {
    return next_ == expected_.size() && model_next_ == expected_.size() && rtl_exit_.empty() &&
           model_exit_.empty();
  }
  // The mismatch to report: the pixel side's first (with an earlier ready mismatch as its
  // `before`), else the first ready mismatch; kind kNone when passed().
  Mismatch first_mismatch() const;
  uint64_t pixels_checked() const { return next_; }
  // Scanlines whose pixels (the end-of-row one included) were compared in value and exit cycle.
  uint64_t scanlines_checked() const { return rows_compared_; }
  // Cycles until the last pixel left (its cycle + 1); 0 before any pixel.
  uint64_t cycles() const { return cycles_; }

 private:
  // Exit cycles waiting for their partner: a FIFO that is empty nearly always (RTL and cycle
  // model in step), so it rewinds instead of allocating.
  class ExitQueue {
   public:
    bool empty() const { return head_ == cycles_.size(); }
    size_t size() const { return cycles_.size() - head_; }
    void push(uint64_t cycle) { cycles_.push_back(cycle); }
    uint64_t pop() {
      const uint64_t c = cycles_[head_++];
      if (head_ == cycles_.size()) {
        cycles_.clear();
        head_ = 0;
      }
      return c;
    }

   private:
    std::vector<uint64_t> cycles_;
    size_t head_ = 0;
  };

  // Every field the RTL drives: x, y, end of row, lane and the configured channels.
  bool same_pixel(const PixelOut& want, const PixelOut& got) const {
    if (want.x != got.x || want.y != got.y || want.end_of_row != got.end_of_row ||
        want.lane != got.lane) {
      return false;
    }
    for (int c = 0; c < channels_; ++c) {
      if (want.colour[c] != got.colour[c]) return false;
    }
    return true;
  }
  // expected_[next_] left the RTL on `cycle`: count it and pair its exit cycle.
  void accept_rtl_pixel(uint64_t cycle) {
    const size_t k = next_++;
    cycles_ = cycle + 1;
    if (model_exit_.empty()) {
      rtl_exit_.push(cycle);
    } else {
      compare_exit(k, cycle, model_exit_.pop());
    }
  }
  void compare_exit(size_t k, uint64_t rtl_cycle, uint64_t model_cycle) {
    if (rtl_cycle != model_cycle) {
      exit_mismatch(k, rtl_cycle, model_cycle);
    } else if (expected_[k].end_of_row) {
      ++rows_compared_;
    }
  }
  // Everything else: ends of rows, mismatches, pixels after a failure or past the end.
  void rtl_pixel_checked(const PixelOut& got, uint64_t cycle);
  void exit_mismatch(size_t k, uint64_t rtl_cycle, uint64_t model_cycle);
  void model_disagrees(uint64_t cycle, int x, int y, int lane, bool eor);
  void ready_mismatch(uint64_t cycle, bool rtl, bool model, const CommandPortState& port);
  void fail(Mismatch m);
  // scanline, y and x of the pixel the output owes next (the last one when none is left).
  void place_at_output(Mismatch& m) const;
  std::string describe(const PixelOut& p) const;
  int scanline_of(size_t k) const;

  std::vector<PixelOut> expected_;
  std::vector<size_t> row_end_;  // index of each scanline's end-of-row pixel
  int channels_;
  int lanes_;
  size_t next_ = 0;        // expected_[next_]: the RTL's next pixel
  size_t model_next_ = 0;  // expected_[model_next_]: the cycle model's next pixel
  int scanline_ = 0;       // scanline of expected_[next_]
  uint64_t rows_compared_ = 0;
  ExitQueue rtl_exit_, model_exit_;  // exit cycles of pixels the other side has not sent yet
  Mismatch first_;                   // the pixel side's first mismatch
  Mismatch ready_;                   // the first ready mismatch
  uint64_t cycles_ = 0;
};

}  // namespace shadesim
