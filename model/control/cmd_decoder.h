// CmdDecoder: rtl/cmd_decoder.sv - the command port's beat decoder. A beat of port_words words
// (model/command_stream.h) is taken apart one item per cycle - the TRIANGLE coefficient words due
// in it (the tail), then at most one header (with a TRIANGLE's words after it, or a run of SPAN
// headers into a span queue), or one MATERIAL / TABLE payload word, or a NOP (the rest is
// padding) - and accepted with its last item. A header waits while the part of the unit it
// changes is busy (the *_i inputs, read through Inputs). With host span setup a SPAN header
// brings start_words payload words, taken like a TRIANGLE's.
//
// The payload FSM is CmdPayload (model/control/cmd_payload.h), owned as payload_ as the RTL
// instantiates cmd_payload as u_payload: decode() reads its state before the edge (in_payload_o,
// tri_payload_o, and pay_rem_q, from which it works out the tail: the RTL keeps that as the
// registers behind tail_n_o and tail_hdr_o), clock() clocks it with the item's wires. The RTL
// decodes every word of the beat as a header in parallel and picks the header's word's results
// (docs/rtl.md, timing); decode() decodes the header's word alone, to the same item.
// Parameters: PORT_WORDS, QUEUED, MAT_BANKED, HOST_SETUP, START_WORDS (N_MAT_FIXED only reaches
// u_payload's configuration writes, which are not timing).
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/command_word.h"
#include "model/control/cmd_payload.h"

namespace shadesim {

class CmdDecoder {
 public:
  using Payload = CmdPayload::Payload;

  CmdDecoder(unsigned port_words, bool queued, bool mat_banked, bool host_setup,
             unsigned start_words)
      : port_words_(port_words),
        queued_(queued),
        mat_banked_(mat_banked),
        host_(host_setup),
        start_words_(start_words) {}

  // The item taken from the beat on the port this cycle: the coefficient words due in the beat
  // (tail), then at most one header, or one MATERIAL / TABLE payload word; n words from pos.
  // Taken on the edge only when cmd_valid.
  struct Item {
    // Coefficient words of a TRIANGLE, or start values of a SPAN (host setup), are due: these
    // come as a tail per beat.
    bool tri_payload = false;
    unsigned tail = 0;      // tail_n: such words taken before the header
    unsigned hdr_pos = 0;   // the header's word in the beat
    bool hdr_here = false;  // a header is in the beat
    CommandWord word;       // word_o: the header, or the payload word at pos without one
    Opcode op = Opcode::kNop;
    bool host_span = false;  // a host-setup SPAN header: its payload is its start values
    unsigned count = 0;      // pay_count: the header's payload words
    unsigned hdr_n = 1;      // words taken with the header
    bool take_hdr = false;   // the header is here and ready
    unsigned n = 0;          // item_n: words taken
    bool beat_done = false;  // ... the rest of the beat

    bool cmd_ready() const { return n > 0 && beat_done; }
    bool span_header() const { return take_hdr && op == Opcode::kSpan; }
    bool tri_header() const { return take_hdr && op == Opcode::kTriangle; }
    bool mat_header() const { return take_hdr && op == Opcode::kMaterial; }
  };

  // Decodes the beat on the port. `in` gives the module's *_i inputs as methods -
  // datapath_empty, mat_other_free, mat_cur_free, sq_full, sq_room, s1_free, tri_bank_free,
  // start_free - each asked only when the header waiting needs it (datapath_empty walks the
  // slot's line), as the RTL's hdr_ready case reads one per opcode.
  template <class Inputs>
  Item decode(const uint64_t* beat, const Inputs& in) const {
    Item item;
    const unsigned beat_left = port_words_ - pos_;
    const bool in_payload = payload_.in_payload();
    const unsigned pay_rem = payload_.pay_rem();
    item.tri_payload = payload_.tri_payload();
    item.tail = item.tri_payload ? std::min(pay_rem, beat_left) : 0;
    item.hdr_pos = pos_ + item.tail;
    item.hdr_here =
        (!in_payload || (item.tri_payload && pay_rem <= beat_left)) && item.hdr_pos < port_words_;
    item.word = CommandWord{beat[item.hdr_here ? item.hdr_pos : pos_]};
    item.op = static_cast<Opcode>(item.word.opcode());
    // Payload words: the header's count, but a host-setup SPAN's count is its start words.
    item.host_span = host_ && item.op == Opcode::kSpan;
    item.count = item.host_span ? start_words_ : item.word.count();
    item.hdr_n = header_words(beat, item, in);
    item.take_hdr = item.hdr_here && header_ready(item, in);
    item.n =
        item.tail + (item.take_hdr ? item.hdr_n : 0) + (in_payload && !item.tri_payload ? 1 : 0);
    item.beat_done = item.n == beat_left;
    return item;
  }

  // Nothing half taken: no payload due and no beat begun.
  bool idle() const { return !payload_.in_payload() && pos_ == 0; }
  bool in_payload() const { return payload_.in_payload(); }
  Payload payload() const { return payload_.payload(); }  // u_payload's pay_op_q
  // span_pay_o: the payload words due are a host-setup SPAN's (the start bank's newest entry).
  bool span_pay() const { return payload_.span_pay(); }

  // The edge: on cmd_valid the item's words are taken (g_beat_pos's item_fire), and u_payload
  // is clocked with hdr_fire = cmd_valid && take_hdr.
  void clock(bool cmd_valid, const Item& item) {
    if (!cmd_valid) return;  // no beat offered: nothing is taken (item_fire, hdr_fire low)
    if (item.n > 0) pos_ = item.beat_done ? 0 : pos_ + item.n;
    payload_.clock(true, item.take_hdr, item.word, item.host_span, item.count, item.hdr_n,
                   item.tail);
  }

 private:
  // hdr_n: the words a header takes with it.
  template <class Inputs>
  unsigned header_words(const uint64_t* beat, const Item& item, const Inputs& in) const {
    // A one-word port: a header taken is the whole beat (g_hdr_one).
    if (port_words_ == 1) return 1;
    if (item.op == Opcode::kNop) return port_words_ - item.hdr_pos;
    if (item.op == Opcode::kTriangle || item.host_span)
      return 1 + std::min(item.count, port_words_ - item.hdr_pos - 1);
    if (item.op == Opcode::kSpan && queued_ && item.hdr_here) {
      // A run of SPAN headers goes into the span queue together, as many as it has room for.
      const unsigned room = in.sq_room();
      unsigned run = 1;
      while (item.hdr_pos + run < port_words_ &&
             CommandWord{beat[item.hdr_pos + run]}.is(Opcode::kSpan))
        ++run;
      return std::max(1u, std::min(run, room));
    }
    return 1;
  }

  // hdr_ready: MATERIAL and TABLE must not change what pixels in flight read, so they wait for
  // an empty datapath - with two material buffers a MATERIAL only for the bank it switches to,
  // and a per-material TABLE (it writes the latest MATERIAL's bank) for that bank.
  template <class Inputs>
  bool header_ready(const Item& item, const Inputs& in) const {
    switch (item.op) {
      case Opcode::kMaterial:
        return mat_banked_ ? in.mat_other_free() : in.datapath_empty();
      case Opcode::kTable:
        return mat_banked_ && item.word.table_per_material() ? in.mat_cur_free()
                                                             : in.datapath_empty();
      case Opcode::kSpan:
        // Host setup: a free start bank entry. Without a span queue a SPAN's setup reads the
        // coefficients as it is taken: not on the edge that writes its triangle's last words.
        if (host_) return in.start_free();
        return queued_ ? !in.sq_full() : in.s1_free() && item.tail == 0;
      case Opcode::kTriangle:
        return in.tri_bank_free();
      default:
        return true;
    }
  }

  unsigned port_words_ = 1;
  bool queued_ = false;
  bool mat_banked_ = false;
  bool host_ = false;
  unsigned start_words_ = 0;
  unsigned pos_ = 0;    // pos_q: the next word of the beat on the port still to be taken
  CmdPayload payload_;  // u_payload: the payload FSM
};

}  // namespace shadesim
