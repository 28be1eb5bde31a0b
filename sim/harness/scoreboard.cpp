#include "sim/harness/scoreboard.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace shadesim {

std::string to_string(Mismatch::Kind kind) {
  switch (kind) {
    case Mismatch::Kind::kNone:
      return "none";
    case Mismatch::Kind::kPixel:
      return "pixel";
    case Mismatch::Kind::kCycle:
      return "cycle";
    case Mismatch::Kind::kReady:
      return "ready";
    case Mismatch::Kind::kExtraPixel:
      return "extra-pixel";
    case Mismatch::Kind::kTimeout:
      return "timeout";
    case Mismatch::Kind::kHang:
      return "hang";
  }
  return "?";
}

Scoreboard::Scoreboard(std::vector<PixelOut> expected, int channels, int lanes)
    : expected_(std::move(expected)), channels_(channels), lanes_(lanes) {
  for (size_t k = 0; k < expected_.size(); ++k) {
    if (expected_[k].end_of_row) row_end_.push_back(k);
  }
}

int Scoreboard::scanline_of(size_t k) const {
  return static_cast<int>(std::lower_bound(row_end_.begin(), row_end_.end(), k) - row_end_.begin());
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

Mismatch Scoreboard::first_mismatch() const {
  if (!failed()) return ready_;
  Mismatch m = first_;
  if (ready_.kind != Mismatch::Kind::kNone && ready_.cycle <= m.cycle) {
    m.before = "cmd_ready_o differed first, on cycle " + std::to_string(ready_.cycle) +
               ": expected " + ready_.expected + ", got " + ready_.got;
  }
  return m;
}

void Scoreboard::place_at_output(Mismatch& m) const {
  m.scanline = scanline_;
  if (expected_.empty()) return;
  const PixelOut& p = expected_[std::min(next_, expected_.size() - 1)];
  m.x = p.x;
  m.y = p.y;
}

void Scoreboard::rtl_pixel_checked(const PixelOut& got, uint64_t cycle) {
  if (failed()) return;
  if (next_ >= expected_.size()) {
    Mismatch m;
    m.kind = Mismatch::Kind::kExtraPixel;
    m.scanline = scanline_;
    m.x = got.x;
    m.y = got.y;
    m.expected = "no more pixels (all " + std::to_string(expected_.size()) + " have left)";
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
  if (want.end_of_row) ++scanline_;
  accept_rtl_pixel(cycle);
}

void Scoreboard::exit_mismatch(size_t k, uint64_t rtl_cycle, uint64_t model_cycle) {
  const PixelOut& p = expected_[k];
  Mismatch m;
  m.kind = Mismatch::Kind::kCycle;
  m.scanline = scanline_of(k);
  m.x = p.x;
  m.y = p.y;
  const std::string which = "pixel " + std::to_string(k) + " " + describe(p);
  m.expected = which + " leaves on cycle " + std::to_string(model_cycle) + " (cycle model)";
  m.got = "it left on cycle " + std::to_string(rtl_cycle) + " (RTL)";
  m.cycle = std::min(rtl_cycle, model_cycle);
  fail(m);
}

void Scoreboard::model_disagrees(uint64_t cycle, int x, int y, int lane, bool eor) {
  // The two reference models describe different streams: a harness or model bug, not the RTL's.
  Mismatch m;
  m.kind = Mismatch::Kind::kCycle;
  m.scanline = scanline_of(model_next_);
  m.x = x;
  m.y = y;
  m.expected = model_next_ < expected_.size()
                   ? "pixel " + std::to_string(model_next_) + " " +
                         describe(expected_[model_next_]) + " (bit-accurate model)"
                   : "no more pixels (bit-accurate model)";
  m.got = "the cycle model's pixel (x=" + std::to_string(x) + " y=" + std::to_string(y) +
          (eor ? " eor" : "") + (lanes_ > 1 ? " lane=" + std::to_string(lane) : "") +
          ") on cycle " + std::to_string(cycle) + ": the reference models disagree";
  m.cycle = cycle;
  fail(m);
}

void Scoreboard::ready_mismatch(uint64_t cycle, bool rtl, bool model,
                                const CommandPortState& port) {
  Mismatch m;
  m.kind = Mismatch::Kind::kReady;
  place_at_output(m);
  char word[32];
  std::snprintf(word, sizeof word, "0x%016llx", static_cast<unsigned long long>(port.word0));
  const std::string on_port =
      port.beat < port.beats
          ? std::string(port.valid ? "beat " : "idle before beat ") + std::to_string(port.beat) +
                " of " + std::to_string(port.beats) + " on the port (cmd_valid_i " +
                (port.valid ? "1" : "0") + ", word 0 " + word + ")"
          : std::string("every beat accepted (cmd_valid_i 0, word 0 ") + word + ")";
  m.expected = std::string("cmd_ready_o ") + (model ? "1" : "0") + " (cycle model), " + on_port;
  m.got = std::string("cmd_ready_o ") + (rtl ? "1" : "0") + " (RTL)";
  m.cycle = cycle;
  ready_ = std::move(m);
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
  m.got = "a beat at (x=" + std::to_string(x) + " y=" + std::to_string(y) + ") with lane mask 0b" +
          bits;
  m.cycle = cycle;
  fail(m);
}

void Scoreboard::rtl_valid_after_end(uint64_t x, uint64_t y, uint64_t mask, uint64_t cycle) {
  if (failed()) return;
  Mismatch m;
  m.kind = Mismatch::Kind::kExtraPixel;
  m.scanline = scanline_;
  m.x = static_cast<int>(x);
  m.y = static_cast<int>(y);
  m.expected = "pix_valid_o 0: all " + std::to_string(expected_.size()) +
               " pixels have left (draining the pipeline)";
  std::string bits;
  for (int j = lanes_ - 1; j >= 0; --j) bits += ((mask >> j) & 1) ? '1' : '0';
  m.got = "pix_valid_o 1 with (x=" + std::to_string(x) + " y=" + std::to_string(y) +
          (lanes_ > 1 ? " lane mask 0b" + bits : std::string()) + ")";
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
    m.expected = std::to_string(expected_.size()) + " pixel exits from the cycle model";
  }
  m.got = "nothing (" + std::to_string(rtl_exit_.size()) + " RTL / " +
          std::to_string(model_exit_.size()) +
          " cycle-model exit cycles not yet paired; the cycle "
          "model sent " +
          std::to_string(model_next_) + " pixels)";
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
