// SetupCtrl: rtl/setup_ctrl.sv - which span is in which of the three span setup stages and when
// it moves (the arithmetic is model/span_setup.h's). A span enters stage 1 whenever it is free,
// moves on when the next stage is free, and leaves stage 3 when the engines load it: setup
// overlaps the previous span's pixels, and back-to-back spans leave no bubble. Not elaborated
// with host span setup.
#pragma once

#include "model/control/span_desc.h"

namespace shadesim {

class SetupCtrl {
 public:
  // The stages' handshakes on this cycle, given whether the engines take stage 3's span.
  struct Moves {
    bool s1_free = false;  // s1_free_o: stage 1 can take a span
    bool s1_move = false;  // s1_move_o: stage 1's span moves to stage 2
    bool s2_move = false;  // s2_move_o: stage 2's span moves to stage 3
  };
  Moves moves(bool eng_load) const {
    Moves m;
    const bool s3_free = !v_[2] || eng_load;
    m.s2_move = v_[1] && s3_free;
    m.s1_move = v_[0] && (!v_[1] || m.s2_move);
    m.s1_free = !v_[0] || m.s1_move;
    return m;
  }
  bool s3_valid() const { return v_[2]; }
  const SpanDesc& s3_span() const { return s_[2]; }
  // busy_o: some stage holds a span.
  bool busy() const { return v_[0] || v_[1] || v_[2]; }

  // The edge: `s1_span` enters stage 1 on s1_load (read only then); the engines take stage 3's
  // on eng_load.
  void clock(bool s1_load, const SpanDesc& s1_span, const Moves& m, bool eng_load) {
    if (m.s2_move) s_[2] = s_[1];
    if (m.s1_move) s_[1] = s_[0];
    if (s1_load) s_[0] = s1_span;
    v_[2] = m.s2_move || (v_[2] && !eng_load);
    v_[1] = m.s1_move || (v_[1] && !m.s2_move);
    v_[0] = s1_load || (v_[0] && !m.s1_move);
  }

 private:
  bool v_[3] = {false, false, false};  // s1_v_q .. s3_v_q
  SpanDesc s_[3];                      // s1_q .. s3_q
};

}  // namespace shadesim
