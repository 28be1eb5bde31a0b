// EngineCtrl: rtl/engine_ctrl.sv - the series engines' run control: which span they run, its
// next beat's position and the pixels left, and when they step. The engines take the span
// waiting for them (setup stage 3, or with host setup the start bank's oldest entry) when idle
// or on the cycle their span's last beat leaves, and step one beat of `lanes` pixels whenever
// the pix register can take one (adv) and no iterative specular unit is busy.
#pragma once

#include <algorithm>

#include "model/control/beat_meta.h"
#include "model/control/span_desc.h"

namespace shadesim {

class EngineCtrl {
 public:
  explicit EngineCtrl(unsigned lanes) : lanes_(lanes) {}

  // The module's combinational outputs on this cycle.
  struct Out {
    bool emit = false;      // emit_o: the engines hand a beat on and step
    bool last_pix = false;  // span_end_o: that beat is the span's last
    bool load = false;      // load_o: the engines take the waiting span
  };
  Out outputs(bool span_valid, bool adv, bool spec_busy) const {
    Out o;
    o.emit = run_ && adv && !spec_busy;
    // 1 <= rem <= lanes on the last beat (rem - 1 < lanes, as the RTL compares it).
    o.last_pix = rem_ - 1 < lanes_;
    const bool take_ready = !run_ || (o.emit && o.last_pix);
    o.load = span_valid && take_ready;
    return o;
  }
  // run_o: the engines hold a span.
  bool run() const { return run_; }
  // The beat they hand to the slot's metadata line (meta_in; valid while they run), with the
  // material bank of their span (material_bank's eng_bank_o).
  BeatMeta beat(const Out& o, int mat) const {
    return {run_, x_,        y_, last_ && o.last_pix, static_cast<int>(std::min(rem_, lanes_)),
            mat,  o.last_pix};
  }

  // The edge: load `span` (read only on o.load), or step.
  void clock(const Out& o, const SpanDesc& span) {
    if (o.load) {
      run_ = true;
      rem_ = static_cast<unsigned>(span.len);
      x_ = span.x0;
      y_ = span.y;
      last_ = span.last;
    } else if (o.emit) {
      if (o.last_pix) run_ = false;
      rem_ -= lanes_;  // wraps after the last beat, as the RTL's rem_q; reloaded before use
      x_ += static_cast<int>(lanes_);
    }
  }

 private:
  unsigned lanes_ = 1;
  bool run_ = false;   // run_q
  unsigned rem_ = 0;   // rem_q: pixels of the span still to leave
  int x_ = 0, y_ = 0;  // x_q, y_q: the next beat's lane 0 pixel
  bool last_ = false;  // last_q: the span ends its row
};

}  // namespace shadesim
