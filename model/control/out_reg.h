// OutReg: rtl/out_reg.sv - the pix port register, one beat of up to `lanes` finished pixels,
// valid/ready. It takes a beat whenever it is empty or its beat is taken (adv), and that
// advance moves the whole pipeline: there is no skid buffer.
#pragma once

#include "model/control/beat_meta.h"

namespace shadesim {

class OutReg {
 public:
  // adv_o: the register can take a beat this cycle.
  bool adv(bool pix_ready) const { return !q_.valid || pix_ready; }
  // pix_valid_o and the beat on the pix port (x, y, mask as a count, eor).
  bool valid() const { return q_.valid; }
  const BeatMeta& beat() const { return q_; }

  // The edge: on adv the register takes `in` when load (the slot's output is a beat), else
  // empties. An empty register's data is never read, so it takes `in`'s fields either way: one
  // copy and no branch on load, which follows the pixel stream and predicts badly.
  void clock(bool adv, bool load, const BeatMeta& in) {
    if (!adv) return;
    q_ = in;
    q_.valid = load;
  }

 private:
  BeatMeta q_;  // pix_valid_o (q_.valid) and the pix_*_o registers
};

}  // namespace shadesim
