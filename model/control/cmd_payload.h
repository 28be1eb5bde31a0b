// CmdPayload: rtl/cmd_payload.sv - cmd_decoder's payload FSM (its instance u_payload): which
// header's payload words are being taken, and how many are still to come. A TRIANGLE's (or, with
// host span setup, a SPAN's) words arrive as the tail of each beat, several per cycle; a
// MATERIAL's or TABLE's one word per cycle.
//
// Only the timing state is kept, as in every class under model/control/:
//   in_payload_q, pay_op_q, pay_rem_q   modelled (in_payload_, pay_op_, pay_rem_)
//   tri_q, tail_q, tail_hdr_q           not modelled: registered copies of what the state above
//                                       says (tri_payload(), min(pay_rem_, port words), a header
//                                       after the tail), kept for timing (docs/rtl.md);
//                                       CmdDecoder::decode works them out from pay_rem()
//   pay_idx_q, cfg_base_q, tbl_mat_q    not modelled: they only address the datapath's registers
//                                       (pay_idx_o, cfg_addr_o, cfg_all_banks_o) and never hold
//                                       a header back
// Outputs: in_payload_o, tri_payload_o and span_pay_o as methods, tail_n_o and tail_hdr_o from
// pay_rem() (CmdDecoder); pay_mat_o and cfg_table_o from payload(); pay_idx_o, cfg_valid_o,
// cfg_all_banks_o and cfg_addr_o not (the configuration writes are the datapath model's).
// Parameters: the RTL works out what a header would start for every word of the beat at once
// (PORT_WORDS, HOST_SETUP and START_WORDS) and takes the header's word's (hdr_sel_i); clock()
// gets the header's alone, with CmdDecoder's host_span, pay_count and hdr_n: the same state.
// N_MAT_FIXED reaches only cfg_valid_o and cfg_addr_o, so none is held here.
#pragma once

#include <cstdint>

#include "model/command_word.h"

namespace shadesim {

class CmdPayload {
 public:
  // pay_e / pay_op_q: which payload is being taken.
  enum class Payload : uint8_t { kSkip, kMaterial, kTriangle, kTable, kSpan };

  bool in_payload() const { return in_payload_; }  // in_payload_o
  // tri_payload_o: the words due come as a tail per beat (a TRIANGLE's or a host SPAN's).
  bool tri_payload() const {
    return in_payload_ && (pay_op_ == Payload::kTriangle || pay_op_ == Payload::kSpan);
  }
  unsigned pay_rem() const { return pay_rem_; }  // pay_rem_o
  // span_pay_o: the words due are a host-setup SPAN's start values.
  bool span_pay() const { return in_payload_ && pay_op_ == Payload::kSpan; }
  Payload payload() const { return pay_op_; }  // pay_op_q

  // The edge (always_comb's next state, always_ff's update). hdr_fire_i: a header `hdr` is taken
  // (a host SPAN when host_span, with pay_count payload words, hdr_n beat words taken with it);
  // else, on cmd_valid while in the payload, the tail (tail_n words) or one MATERIAL / TABLE word.
  void clock(bool cmd_valid, bool hdr_fire, CommandWord hdr, bool host_span, unsigned pay_count,
             unsigned hdr_n, unsigned tail_n) {
    if (hdr_fire) {
      start(hdr, host_span, pay_count, hdr_n);
    } else if (cmd_valid && in_payload_) {  // pay_fire
      const unsigned pay_take = tri_payload() ? tail_n : 1;
      if (pay_take == pay_rem_) in_payload_ = false;  // the payload's last word
      pay_rem_ = (pay_rem_ - pay_take) & CommandWord::kFieldMask;
    }
  }

 private:
  // hdr_fire_i: the unique case on the header's opcode.
  void start(CommandWord hdr, bool host_span, unsigned pay_count, unsigned hdr_n) {
    const unsigned hdr_count = hdr.count();
    pay_rem_ = hdr_count;
    switch (static_cast<Opcode>(hdr.opcode())) {
      case Opcode::kMaterial:
        pay_op_ = Payload::kMaterial;
        in_payload_ = hdr_count != 0;
        break;
      // The coefficient words that came with the header are already taken.
      case Opcode::kTriangle:
        start_tail(Payload::kTriangle, hdr_count, hdr_n);
        break;
      case Opcode::kTable:
        pay_op_ = Payload::kTable;
        in_payload_ = hdr_count != 0;
        break;
      // Host setup: the start values that came with the header are already taken.
      case Opcode::kSpan:
        if (host_span) {
          start_tail(Payload::kSpan, pay_count, hdr_n);
        } else {
          pay_op_ = Payload::kSkip;
          in_payload_ = false;
        }
        break;
      default:  // END_FRAME and unknown opcodes carry no payload
        pay_op_ = Payload::kSkip;
        in_payload_ = false;
        break;
    }
  }

  // A TRIANGLE or host-setup SPAN: `count` payload words, hdr_n - 1 of them taken with the header.
  void start_tail(Payload op, unsigned count, unsigned hdr_n) {
    pay_op_ = op;
    pay_rem_ = (count - hdr_n + 1) & CommandWord::kFieldMask;
    in_payload_ = count > hdr_n - 1;
  }

  bool in_payload_ = false;          // in_payload_q
  Payload pay_op_ = Payload::kSkip;  // pay_op_q
  unsigned pay_rem_ = 1;             // pay_rem_q: payload words still to come
};

}  // namespace shadesim
