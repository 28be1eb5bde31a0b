// SpanQueue: rtl/span_queue.sv with TRI_QUEUE > 1 - the SPAN headers between the command
// decoder and span setup, and the triangle queue's bank bookkeeping: which coefficient bank a
// TRIANGLE writes, which one each queued span reads, and how many queued spans read each. A run
// of SPAN headers of one beat enters together; setup stage 1 takes the head whenever it is free;
// a TRIANGLE waits until no queued span reads the bank it would write. With TRI_QUEUE 1 the
// module is wires (a SPAN goes straight to stage 1, one bank) and the model has no SpanQueue.
#pragma once

#include <array>
#include <cstdint>

#include "model/command_word.h"
#include "model/control/span_desc.h"

namespace shadesim {

class SpanQueue {
 public:
  static constexpr int kSpansPerTriangle = 4;  // entries per bank (CycleConfig::span_queue())
  static constexpr int kMaxBanks = 8;          // UnitConfig::tri_queue's range

  // tri_queue banks (2..kMaxBanks, checked by CycleModel), kSpansPerTriangle * tri_queue entries.
  explicit SpanQueue(int tri_queue)
      : banks_(tri_queue), size_(static_cast<unsigned>(kSpansPerTriangle * tri_queue)) {}

  bool full() const { return count_ == size_; }                 // full_o
  unsigned room() const { return size_ - count_; }              // room_o
  bool empty() const { return count_ == 0; }                    // empty_o
  bool pop(bool s1_free) const { return !empty() && s1_free; }  // s1_load_o
  const SpanDesc& head() const { return q_[head_].span; }       // s1_span_o
  int head_mat() const { return q_[head_].mat; }                // s1_mat_o
  // next_bank_o: the bank the next TRIANGLE writes; tri_bank_free_o: no queued span reads it.
  int next_bank() const { return wr_bank_ == banks_ - 1 ? 0 : wr_bank_ + 1; }
  bool tri_bank_free() const { return bank_spans_[static_cast<size_t>(next_bank())] == 0; }

  // The edge: stage 1 takes the head on pop; span_n SPAN headers from beat word hdr_pos on enter
  // on span_fire, reading the latest TRIANGLE's bank and the latest MATERIAL's bank mat_wr; a
  // TRIANGLE header (tri_fire) moves the write bank on.
  void clock(bool pop, bool span_fire, const uint64_t* beat, unsigned hdr_pos, unsigned span_n,
             int mat_wr, bool tri_fire) {
    if (pop) {
      --bank_spans_[static_cast<size_t>(q_[head_].bank)];
      if (++head_ == size_) head_ = 0;
      --count_;
    }
    if (span_fire) {
      for (unsigned k = 0; k < span_n; ++k) {
        q_[tail_] = {SpanDesc::of(CommandWord{beat[hdr_pos + k]}), wr_bank_, mat_wr};
        if (++tail_ == size_) tail_ = 0;
      }
      bank_spans_[static_cast<size_t>(wr_bank_)] += static_cast<int>(span_n);
      count_ += span_n;
    }
    if (tri_fire) wr_bank_ = next_bank();
  }

 private:
  struct Entry {
    SpanDesc span;  // sq_span_q
    int bank = 0;   // sq_bank_q: its triangle's coefficient bank
    int mat = 0;    // sq_mat_q: its material bank
  };
  int banks_ = 2;
  unsigned size_ = 0;
  // The ring, sized for the largest queue so it lives in the model, not behind a pointer.
  std::array<Entry, std::size_t{kSpansPerTriangle} * kMaxBanks> q_{};
  unsigned head_ = 0, tail_ = 0, count_ = 0;  // head_q, tail_q, count_q
  std::array<int, kMaxBanks> bank_spans_{};   // bank_spans_q: queued spans per bank
  int wr_bank_ = 0;                           // wr_bank_q: the latest TRIANGLE's bank
};

}  // namespace shadesim
