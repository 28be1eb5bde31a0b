#include "sim/harness/cycle_model.h"

namespace shadesim {
namespace {
constexpr unsigned kOpMaterial = 0x01, kOpTriangle = 0x02, kOpSpan = 0x03, kOpTable = 0x04;
}

CycleModel::Edge CycleModel::clock(bool cmd_valid, uint64_t word, bool pix_ready) {
  Edge e;
  // ---- combinational, from the state before the edge (same equations as the RTL) ----
  const bool adv = !pix_valid_ || pix_ready;
  const bool emit = run_ && adv;
  const bool last_pix = rem_ == 1;
  const bool load_eng = s_[2].valid && (!run_ || (emit && last_pix));
  const bool s3_free = !s_[2].valid || load_eng;
  const bool s2_move = s_[1].valid && s3_free;
  const bool s1_move = s_[0].valid && (!s_[1].valid || s2_move);
  const bool s1_free = !s_[0].valid || s1_move;
  const bool datapath_empty = !s_[0].valid && !s_[1].valid && !s_[2].valid && !run_;

  const unsigned op = static_cast<unsigned>(word >> 56) & 0xFF;
  const unsigned count = static_cast<unsigned>(word & 0xFFFF);
  bool hdr_ready = true;
  if (op == kOpMaterial) hdr_ready = datapath_empty;
  if (op == kOpSpan) hdr_ready = s1_free;
  e.cmd_ready = in_payload_ || hdr_ready;
  e.cmd_fire = cmd_valid && e.cmd_ready;
  const bool hdr_fire = e.cmd_fire && !in_payload_;
  const bool pay_fire = e.cmd_fire && in_payload_;
  const bool span_fire = hdr_fire && op == kOpSpan;

  e.pix_fire = pix_valid_ && pix_ready;
  e.pix_eor = pix_eor_;
  e.pix_x = pix_x_;
  e.pix_y = pix_y_;

  // ---- the edge ----
  if (adv) {
    if (emit) {
      pix_x_ = x_;
      pix_y_ = y_;
      pix_eor_ = last_ && last_pix;
    }
    pix_valid_ = run_;
  }
  if (load_eng) {
    run_ = true;
    rem_ = static_cast<unsigned>(s_[2].len);
    x_ = s_[2].x0;
    y_ = s_[2].y;
    last_ = s_[2].last;
  } else if (emit) {
    if (last_pix) run_ = false;
    --rem_;
    ++x_;
  }
  if (s2_move) s_[2] = s_[1];
  else if (load_eng) s_[2].valid = false;
  if (s1_move) s_[1] = s_[0];
  else if (s2_move) s_[1].valid = false;
  if (span_fire) {
    s_[0].valid = true;
    s_[0].y = static_cast<int>((word >> 32) & 0xFFFF);
    s_[0].x0 = static_cast<int>((word >> 16) & 0xFFFF);
    s_[0].len = static_cast<int>(count);
    s_[0].last = ((word >> 55) & 1) != 0;
  } else if (s1_move) {
    s_[0].valid = false;
  }

  if (hdr_fire) {
    pay_idx_ = 0;
    pay_last_ = (count - 1) & 0xFFFF;
    switch (op) {
      case kOpMaterial: pay_op_ = Payload::kMaterial; in_payload_ = count != 0; break;
      case kOpTriangle: pay_op_ = Payload::kTriangle; in_payload_ = count != 0; break;
      case kOpTable: pay_op_ = Payload::kTable; in_payload_ = count != 0; break;
      default: pay_op_ = Payload::kSkip; in_payload_ = false; break;
    }
  } else if (pay_fire) {
    if (pay_idx_ == pay_last_) in_payload_ = false;
    pay_idx_ = (pay_idx_ + 1) & 0xFFFF;
  }
  return e;
}

CycleRun CycleModel::run(const std::vector<uint64_t>& words, const Stimulus& stim) {
  CycleModel m;
  CommandDriver driver(words, stim);
  CycleRun r;
  uint64_t cycle = 0;
  while (!driver.done() || !m.idle()) {
    const bool ready = stim.pix_ready(cycle);
    if (m.pix_valid_ && !ready) ++r.backpressure_cycles;
    const Edge e = m.clock(driver.valid(), driver.word(), ready);
    if (driver.valid() && !e.cmd_fire) ++r.cmd_stall_cycles;
    driver.clock(e.cmd_fire);
    if (e.pix_fire) {
      ++r.pixels;
      if (e.pix_eor) r.scanlines.push_back({e.pix_y, cycle, e.pix_x});
    }
    ++cycle;
  }
  r.cycles = cycle;
  return r;
}

}  // namespace shadesim
