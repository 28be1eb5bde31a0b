// StartBank: with host span setup (UnitConfig::span_setup kHost) the unit's start values come
// from the SPAN payload; rtl/start_bank.sv holds them until the engines load them. The values
// are the series format's raw bits, so the datapath model only reads them out per series
// (operator()). The cycle model keeps the bank's timing (clock() and the outputs before it): a
// ring of `depth` entries, the newest still filling while its SPAN's payload words come, the
// oldest loaded by the engines once complete.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "model/command_word.h"
#include "model/control/span_desc.h"
#include "model/span_setup.h"
#include "model/start_packing.h"

namespace shadesim {

class StartBank {
 public:
  static constexpr unsigned kMaxDepth = 2;  // DEPTH: 1 or 2 entries (checked by CycleModel)

  StartBank() = default;
  explicit StartBank(unsigned depth) : depth_(depth) {}

  // Series i's (v, d, d2) from a SPAN's start values (StartLayout order).
  SeriesStart operator()(const std::vector<int64_t>& starts, int i) const {
    const size_t at = static_cast<size_t>(i) * StartLayout::kValuesPerSeries;
    return {starts[at], starts[at + 1], starts[at + 2]};
  }

  // ---- timing -------------------------------------------------------------------------------
  // valid_o: the oldest entry is complete (filling: the decoder's payload words due are the
  // newest entry's, span_pay).
  bool valid(bool filling) const { return count_ > (filling ? 1u : 0u); }
  // free_o: a SPAN header may be taken - an entry is free, or the oldest leaves on this edge.
  bool free(bool load) const { return count_ < depth_ || load; }
  bool empty() const { return count_ == 0; }                  // empty_o
  const SpanDesc& head_span() const { return q_[rd_].span; }  // span_o
  int head_mat() const { return q_[rd_].mat; }                // mat_o

  // The edge: the engines take the oldest entry on load; a SPAN header taken (span_fire) writes
  // the next entry with its span, in material bank mat.
  void clock(bool load, bool span_fire, CommandWord header, int mat) {
    if (load) {
      if (++rd_ == depth_) rd_ = 0;
      --count_;
    }
    if (span_fire) {
      q_[wr_] = {SpanDesc::of(header), mat};
      if (++wr_ == depth_) wr_ = 0;
      ++count_;
    }
  }

 private:
  struct Entry {
    SpanDesc span;  // span_q
    int mat = 0;    // mat_q
  };
  unsigned depth_ = 1;
  std::array<Entry, kMaxDepth> q_{};
  unsigned rd_ = 0, wr_ = 0, count_ = 0;  // rd_q, wr_q, count_q
};

}  // namespace shadesim
