// SpanSource: rtl/span_source.sv - shade_unit's span intake (its instance u_span_source): where
// the engines' next span comes from. Unit span setup (g_unit_setup): SPAN headers into the span
// queue (u_span_queue: SpanQueue), TRIANGLE coefficients into the coefficient banks (u_coef_bank),
// and the three setup stages (u_setup_ctrl: SetupCtrl). Host span setup (g_host_setup): each SPAN
// carries its start values into the start bank (u_start_bank: StartBank). Either way the engines
// see a span at stage 3 (s3_valid_o, s3_span_o).
//
// coef_bank.sv has no model class: it holds coefficients, which never hold a cycle back (which
// bank a TRIANGLE writes and when it may is span_queue's). span_queue with TRI_QUEUE 1
// (g_no_span_queue) is wires - a SPAN header goes straight into setup stage 1 - and is written
// out here; SpanQueue is clocked only with tri_queue > 1. Parameters: HOST_SETUP, TRI_QUEUE and
// START_DEPTH; the others (PORT_WORDS, XY_BITS, N_COEF, COEF_*WL, OFS_BITS, N_SER, SERIES_WL)
// only size the datapath. Which generate branch and whether the queue is elaborated is decided
// once, at construction.
#pragma once

#include <algorithm>
#include <cstdint>

#include "model/command_word.h"
#include "model/control/setup_ctrl.h"
#include "model/control/span_desc.h"
#include "model/control/span_queue.h"
#include "model/start_bank.h"

namespace shadesim {

class SpanSource {
 public:
  // host_setup: HOST_SETUP; tri_queue: TRI_QUEUE (1..SpanQueue::kMaxBanks, 1 with host setup);
  // start_depth: START_DEPTH (1..StartBank::kMaxDepth). Checked by CycleModel.
  SpanSource(bool host_setup, int tri_queue, unsigned start_depth)
      : host_(host_setup),
        queued_(tri_queue > 1),
        queue_(std::max(tri_queue, 2)),  // (one bank: no queue, built but never clocked)
        start_(start_depth) {}

  // ---- outputs before the edge, in the order their combinational paths run ----------------
  // s3_valid_o: the engines may load a span (host: the start bank's oldest entry is complete;
  // span_pay: the decoder's payload words due fill its newest).
  bool s3_valid(bool span_pay) const { return host_ ? start_.valid(span_pay) : setup_.s3_valid(); }
  const SpanDesc& s3_span() const {  // s3_span_o
    return host_ ? start_.head_span() : setup_.s3_span();
  }

  // s1_free_o, s1_move_o, s2_move_o: the setup stages' handshakes, given eng_load_i (all low
  // with host setup).
  SetupCtrl::Moves moves(bool eng_load) const {
    return host_ ? SetupCtrl::Moves{} : setup_.moves(eng_load);
  }
  // u_span_queue's sq_pop: its head enters setup stage 1 (s1_load_o with a queue).
  bool sq_pop(const SetupCtrl::Moves& m) const { return queued_ && queue_.pop(m.s1_free); }

  // What the decoder waits on. It reads sq_full_o and sq_room_o only with a span queue and
  // start_free_o only with host setup (its QUEUED and HOST_SETUP select them), so these give the
  // queue's and the start bank's values and skip the constants the other configurations tie
  // them to (0, 1 or 0, and 0).
  bool sq_full() const { return queue_.full(); }                // sq_full_o
  unsigned sq_room() const { return queue_.room(); }            // sq_room_o
  bool sq_empty() const { return !queued_ || queue_.empty(); }  // sq_empty_o
  // tri_bank_free_o: the next coefficient bank is free (one bank, or host setup: always).
  bool tri_bank_free() const { return !queued_ || queue_.tri_bank_free(); }
  // start_free_o: a start bank entry is free, or the oldest leaves on eng_load.
  bool start_free(bool eng_load) const { return start_.free(eng_load); }
  // busy_o: a span in setup, or in the start bank.
  bool busy() const { return host_ ? !start_.empty() : setup_.busy(); }

  // s1_load_o, once the decoder's span_fire is known: the queue's head, or the SPAN header taken
  // (no queue); never with host setup.
  bool s1_load(bool sq_pop, bool span_fire) const { return queued_ ? sq_pop : span_fire && !host_; }
  // s1_mat_o: the material bank of the span entering stage 1 (host: of the start bank's oldest);
  // mat_wr: mat_wr_i, the latest MATERIAL's bank.
  int s1_mat(int mat_wr) const {
    return host_ ? start_.head_mat() : queued_ ? queue_.head_mat() : mat_wr;
  }

  // ---- the edge: u_start_bank, or u_setup_ctrl then u_span_queue (setup stage 1 reads the
  // queue's head as it was before the edge). The decoder's item: span_fire_i / tri_fire_i (a
  // SPAN / TRIANGLE header taken), word_i (the header), hdr_pos_i and hdr_n_i (span_n_i: the
  // SPAN headers of a run from that beat word on).
  void clock(const SetupCtrl::Moves& moves, bool sq_pop, bool eng_load, bool span_fire,
             bool tri_fire, const uint64_t* beat, CommandWord word, unsigned hdr_pos,
             unsigned hdr_n, int mat_wr) {
    if (host_) {
      start_.clock(eng_load, span_fire, word, mat_wr);
    } else if (queued_) {
      setup_.clock(sq_pop, queue_.head(), moves, eng_load);
      queue_.clock(sq_pop, span_fire, beat, hdr_pos, hdr_n, mat_wr, tri_fire);
    } else {
      setup_.clock(span_fire, SpanDesc::of(word), moves, eng_load);  // g_no_span_queue
    }
  }

 private:
  bool host_ = false;    // HOST_SETUP: g_host_setup (StartBank), else g_unit_setup
  bool queued_ = false;  // TRI_QUEUE > 1: span_queue's g_span_queue (SpanQueue)
  // The instances, named as span_source.sv's.
  SpanQueue queue_;  // u_span_queue (queued_ only)
  SetupCtrl setup_;  // u_setup_ctrl (not with host_)
  StartBank start_;  // u_start_bank (host_ only)
};

}  // namespace shadesim
