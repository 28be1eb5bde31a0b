// MaterialBank: rtl/material_bank.sv's control with two material buffers (MATERIAL_BUFFERS 2):
// which bank the latest MATERIAL writes (a MATERIAL header switches it), the bank of each span
// on its way - setup stages 1..3 (or the start bank) and the engines - and per bank the spans
// taken whose last beat has not yet left the slot. A MATERIAL waits only until no span in flight
// reads the bank it switches to; a per-material TABLE until none reads the latest MATERIAL's.
// With one buffer the module keeps nothing (every span reads bank 0, MATERIAL and TABLE wait
// for the empty datapath) and the model does not clock it.
#pragma once

namespace shadesim {

class MaterialBank {
 public:
  // host_setup: spans wait in the start bank, not in setup stages.
  explicit MaterialBank(bool host_setup) : host_(host_setup) {}

  int wr_bank() const { return wr_; }                       // wr_bank_o
  bool other_free() const { return spans_[1 - wr_] == 0; }  // other_free_o
  bool cur_free() const { return spans_[wr_] == 0; }        // cur_free_o
  int eng_bank() const { return eng_; }                     // eng_bank_o

  // The edge. span_n spans are taken on span_fire (into the latest MATERIAL's bank); a span
  // enters setup stage 1 (s1_load) with bank s1_bank, or with host setup the engines load the
  // start bank's oldest, of bank s1_bank; leave: a span's last beat of bank leave_bank leaves
  // the slot.
  void clock(bool mat_fire, bool span_fire, int span_n, bool s1_load, int s1_bank, bool s1_move,
             bool s2_move, bool eng_load, bool leave, int leave_bank) {
    // Written as selects, not branches: these follow the spans and pixels, which a branch
    // predictor guesses badly, and each is one register's next value.
    spans_[wr_] += span_fire ? span_n : 0;
    spans_[leave_bank] -= leave ? 1 : 0;
    wr_ ^= mat_fire ? 1 : 0;
    eng_ = eng_load ? (host_ ? s1_bank : s_mat_[2]) : eng_;
    s_mat_[2] = s2_move ? s_mat_[1] : s_mat_[2];
    s_mat_[1] = s1_move ? s_mat_[0] : s_mat_[1];
    s_mat_[0] = s1_load ? s1_bank : s_mat_[0];
  }

 private:
  bool host_ = false;
  int wr_ = 0;                // mat_wr_q
  int spans_[2] = {0, 0};     // mat_spans_q: per bank, spans taken and not out of the slot
  int s_mat_[3] = {0, 0, 0};  // s1_mat_q .. s3_mat_q
  int eng_ = 0;               // eng_mat_q
};

}  // namespace shadesim
