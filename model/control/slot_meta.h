// SlotMeta: rtl/slot_meta.sv - the metadata line beside the specular slots, so a beat's position,
// lanes, end flags and material bank reach the pix register with the slots' results. Three
// shapes, chosen once by the slot's timing as the RTL's generate blocks are:
//   iterative (interval > 1): one pending beat, captured when the slots start it and handed on
//     when they are done, on the edge of the next start (out_adv = adv && !spec_busy);
//   pipelined, latency L > 0: an L-deep line moving on every advance;
//   latency 0 (ideal, none): no register, the engines' beat goes straight on.
#pragma once

#include <cstddef>
#include <vector>

#include "model/control/beat_meta.h"

namespace shadesim {

class SlotMeta {
 public:
  SlotMeta(int latency, bool iterative)
      : iterative_(iterative), line_(iterative ? 0 : static_cast<size_t>(latency)) {}

  // out_adv_o: the pix register takes the line's output beat on this edge (given it can, adv).
  bool out_adv(bool adv, bool spec_busy) const { return adv && !(iterative_ && spec_busy); }
  // valid_o / meta_o: the line's output beat; with no line, the engines' beat `in`.
  const BeatMeta& out(const BeatMeta& in) const {
    if (iterative_) return pend_;
    return line_.empty() ? in : line_[pos_];
  }
  // empty_o: no beat in the line. Walks the line: only MATERIAL and TABLE headers ask.
  bool empty() const {
    if (iterative_) return !pend_.valid;
    for (const BeatMeta& b : line_) {
      if (b.valid) return false;
    }
    return true;
  }

  // The edge: on out_adv the line takes the engines' beat `in` (valid: they hold a span).
  void clock(bool out_adv, const BeatMeta& in) {
    if (!out_adv) return;
    if (iterative_) {
      pend_ = in;
    } else if (!line_.empty()) {
      // The RTL shifts the line by one stage; a ring whose oldest entry is line_[pos_] gives the
      // same output with one write per advance instead of L copies.
      line_[pos_] = in;
      if (++pos_ == line_.size()) pos_ = 0;
    }
  }

 private:
  bool iterative_ = false;
  BeatMeta pend_;               // iterative: the beat in the slots (pend_v_q, pend_q)
  std::vector<BeatMeta> line_;  // pipelined: line_v_q / line_q as a ring, sized once
  size_t pos_ = 0;              // ... its oldest entry, the line's output
};

}  // namespace shadesim
