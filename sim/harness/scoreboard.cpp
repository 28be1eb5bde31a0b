#include "sim/harness/scoreboard.h"

#include <sstream>

namespace shadesim {

std::string to_string(Mismatch::Kind kind) {
  switch (kind) {
    case Mismatch::Kind::kNone: return "none";
    case Mismatch::Kind::kPixel: return "pixel";
    case Mismatch::Kind::kCycle: return "cycle";
    case Mismatch::Kind::kExtraPixel: return "extra-pixel";
    case Mismatch::Kind::kTimeout: return "timeout";
    case Mismatch::Kind::kHang: return "hang";
  }
  return "?";
}

Scoreboard::Scoreboard(std::vector<PixelOut> expected, int channels, int lanes)
    : expected_(std::move(expected)), channels_(channels), lanes_(lanes) {
  for (const auto& p : expected_) expected_rows_ += p.end_of_row ? 1 : 0;
}

std::string Scoreboard::describe(const PixelOut& p) const {
  std::ostringstream os;
  os << "(x=" << p.x << " y=" << p.y << " colour=";
  for (int c = 0; c < channels_; ++c) os << (c ? "," : "") << p.colour[c];
  os << (p.end_of_row ? " eor" : "");
  if (lanes_ > 1) os << " lane=" << p.lane;
  os << ')';
  return os.str();
}

void Scoreboard::fail(Mismatch m) {
  if (!failed()) first_ = std::move(m);
}

void Scoreboard::rtl_pixel_checked(const PixelOut& got, uint64_t cycle) {
  if (failed()) return;
  if (next_ >= expected_.size()) {
    Mismatch m;
    m.kind = Mismatch::Kind::kExtraPixel;
    m.scanline = scanline_;
    m.x = got.x;
    m.y = got.y;
    m.expected = "no more pixels";
    m.got = describe(got);
    m.cycle = cycle;
    fail(m);
    return;
  }
  const PixelOut& want = expected_[next_];
  if (!same_pixel(want, got)) {
    Mismatch m;
    m.kind = Mismatch::Kind::kPixel;
    m.scanline = scanline_;
    m.x = want.x;
    m.y = want.y;
    m.expected = describe(want);
    m.got = describe(got);
    m.cycle = cycle;
    fail(m);
    return;
  }
  ++next_;
  cycles_ = cycle + 1;
  if (want.end_of_row) {
    ++scanline_;
    rtl_rows_.push_back({got.y, cycle, got.x});
    rtl_done_.push_back({got.y, cycle, got.x});
    compare_rows();
  }
}

void Scoreboard::model_scanline(const ScanlineDone& done) {
  if (failed()) return;
  model_rows_.push_back(done);
  compare_rows();
}

void Scoreboard::compare_rows() {
  while (!failed() && !rtl_rows_.empty() && !model_rows_.empty()) {
    const ScanlineDone r = rtl_rows_.front(), m = model_rows_.front();
    rtl_rows_.pop_front();
    model_rows_.pop_front();
    if (r.y != m.y || r.cycle != m.cycle) {
      Mismatch mm;
      mm.kind = Mismatch::Kind::kCycle;
      mm.scanline = static_cast<int>(rows_compared_);
      mm.y = m.y;
      mm.x = r.x;
      mm.expected = "y=" + std::to_string(m.y) + " done at cycle " + std::to_string(m.cycle) +
                    " (cycle model)";
      mm.got = "y=" + std::to_string(r.y) + " done at cycle " + std::to_string(r.cycle) + " (RTL)";
      mm.cycle = r.cycle < m.cycle ? r.cycle : m.cycle;
      fail(mm);
      return;
    }
    ++rows_compared_;
  }
}

void Scoreboard::rtl_bad_mask(uint64_t x, uint64_t y, uint64_t mask, uint64_t cycle) {
  if (failed()) return;
  Mismatch m;
  m.kind = Mismatch::Kind::kPixel;
  m.scanline = scanline_;
  m.x = static_cast<int>(x);
  m.y = static_cast<int>(y);
  m.expected = next_ < expected_.size() ? describe(expected_[next_]) + " in a beat of lanes 0..n-1"
                                        : "no more pixels";
  std::string bits;
  for (int j = lanes_ - 1; j >= 0; --j) bits += ((mask >> j) & 1) ? '1' : '0';
  m.got = "a beat at (x=" + std::to_string(x) + " y=" + std::to_string(y) + ") with lane mask 0b" + bits;
  m.cycle = cycle;
  fail(m);
}

void Scoreboard::timeout(uint64_t cycle) {
  Mismatch m;
  m.kind = Mismatch::Kind::kTimeout;
  m.scanline = scanline_;
  if (next_ < expected_.size()) {
    m.x = expected_[next_].x;
    m.y = expected_[next_].y;
    m.expected = describe(expected_[next_]) + ", pixel " + std::to_string(next_) + " of " +
                 std::to_string(expected_.size());
  } else {
    m.expected = std::to_string(expected_rows_) + " scanline completions from both models";
  }
  m.got = "nothing (RTL rows " + std::to_string(rtl_rows_.size()) + " / cycle-model rows " +
          std::to_string(model_rows_.size()) + " not yet paired)";
  m.cycle = cycle;
  fail(m);
}

void Scoreboard::hang(uint64_t cycle, uint64_t quiet_since, uint64_t limit) {
  Mismatch m;
  m.kind = Mismatch::Kind::kHang;
  m.scanline = scanline_;
  if (next_ < expected_.size()) {
    m.x = expected_[next_].x;
    m.y = expected_[next_].y;
    m.expected = describe(expected_[next_]) + ", pixel " + std::to_string(next_) + " of " +
                 std::to_string(expected_.size());
  }
  m.got = "no pix_valid_o for " + std::to_string(cycle - quiet_since + 1) + " cycles (" +
          std::to_string(quiet_since) + ".." + std::to_string(cycle) + "; watchdog limit " +
          std::to_string(limit) + ")";
  m.cycle = cycle;
  fail(m);
}

}  // namespace shadesim
