#include "model/cycle_estimate.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace shadesim {
namespace {

using Cycle = int64_t;
// Before the first span: far enough back that no max() picks it.
constexpr Cycle kLongAgo = std::numeric_limits<Cycle>::min() / 4;

// The spans' side of the recurrence: setup stages, engines, slot (see the header).
class SpanPipe {
 public:
  explicit SpanPipe(const CycleConfig& unit)
      : queued_(unit.tri_queue > 1),
        interval_(unit.slot.interval),
        latency_(unit.slot.latency),
        lanes_(static_cast<uint64_t>(unit.lanes)),
        depth_(static_cast<size_t>(unit.start_depth)) {
    prev_.fill(kLongAgo);
    loads_.fill(kLongAgo);
    // The entries of the last span_queue() spans are all the decoder asks for (room in the
    // queue); a power-of-two ring holds them.
    size_t ring = 1;
    while (ring < static_cast<size_t>(unit.span_queue())) ring *= 2;
    entry_.assign(queued_ ? ring : 0, kLongAgo);
    ring_mask_ = ring - 1;
  }

  // The span taken by the decoder on cycle `taken`: returns the cycle its last pixel leaves.
  Cycle add(Cycle taken, uint64_t len) {
    std::array<Cycle, CycleEstimate::kSetupStages + 1> s;
    // A queued span enters s1 the cycle after it was queued, once s1 is free.
    s[0] = queued_ ? std::max(taken + 1, prev_[1]) : taken;
    for (int i = 1; i < CycleEstimate::kSetupStages; ++i)
      s[i] = std::max(s[i - 1] + 1, prev_[i + 1]);
    // The engines load once s3 holds the span and they idle or emit their last beat.
    s[CycleEstimate::kSetupStages] = std::max(s[CycleEstimate::kSetupStages - 1] + 1, last_emit_);
    const Cycle first = std::max(s[CycleEstimate::kSetupStages] + 1, last_emit_ + interval_);
    first_emit_ = first;
    last_emit_ = first + static_cast<Cycle>(CycleEstimate::beats(len, lanes_) - 1) * interval_;
    prev_ = s;
    if (queued_) entry_[spans_ & ring_mask_] = s[0];
    last_leave_ = last_emit_ + latency_ + 1;
    ++spans_;
    return last_leave_;
  }

  // Host span setup: the span whose start values are all in on cycle `done` (its header's, or
  // its last payload words'): the engines load it from the start bank on the next cycle once
  // they idle or emit their last beat. Returns the cycle its last pixel leaves.
  Cycle add_host(Cycle done, uint64_t len) {
    const Cycle load = std::max(done + 1, last_emit_);
    loads_[spans_ % loads_.size()] = load;
    const Cycle first = std::max(load + 1, last_emit_ + interval_);
    first_emit_ = first;
    last_emit_ = first + static_cast<Cycle>(CycleEstimate::beats(len, lanes_) - 1) * interval_;
    last_leave_ = last_emit_ + latency_ + 1;
    ++spans_;
    return last_leave_;
  }
  // Host span setup: the first cycle a SPAN header finds a start bank entry free - the entry
  // of the span start_depth places back leaves for the engines on it (or left before).
  Cycle start_entry_free() const {
    return spans_ >= depth_ ? loads_[(spans_ - depth_) % loads_.size()] : 0;
  }

  size_t spans() const { return spans_; }
  // Cycle span k entered s1 (queued units; one of the last span_queue() spans).
  Cycle entry(size_t k) const { return entry_[k & ring_mask_]; }
  // Cycle the latest span entered s1.
  Cycle last_entry() const { return prev_[0]; }
  // Earliest cycle on which s1 is free for the next span (unqueued decoder).
  Cycle s1_free() const { return prev_[1]; }
  // Earliest cycle on which the datapath is empty: the last pixel has left the slot.
  Cycle empty() const { return spans_ ? last_leave_ : 0; }
  Cycle last_leave() const { return last_leave_; }
  // The latest span's first and last emit.
  Cycle first_emit() const { return first_emit_; }
  Cycle last_emit() const { return last_emit_; }
  // Spans queued and not yet in s1 on cycle c; c must not decrease between calls.
  // (Spans more than span_queue() back entered s1 before the decoder could queue the latest.)
  size_t queued_on(Cycle c) {
    popped_ = std::max(popped_, spans_ - std::min(spans_, entry_.size()));
    while (popped_ < spans_ && entry(popped_) < c) ++popped_;
    return spans_ - popped_;
  }

 private:
  bool queued_;
  Cycle interval_, latency_;
  uint64_t lanes_;
  size_t depth_;                  // start bank entries (host span setup)
  std::array<Cycle, 2> loads_{};  // ... and the latest spans' engine loads from it
  std::array<Cycle, CycleEstimate::kSetupStages + 1> prev_;  // the previous span's stage entries
  Cycle first_emit_ = kLongAgo;
  Cycle last_emit_ = kLongAgo;
  Cycle last_leave_ = kLongAgo;
  size_t spans_ = 0;
  std::vector<Cycle> entry_;  // ring of the latest spans' s1 entries
  size_t ring_mask_ = 0;
  size_t popped_ = 0;
};

// CycleBreakdown without the clock. With no back-pressure a cycle is a pixel cycle or a unit
// stall exactly when it lies in a span's busy interval (pipelined slot: its pixels leave,
// [F + latency + 1, E + latency + 1]; iterative: [F + 1, E + interval + 1], the unit holding a
// pixel or one leaving); every other cycle is a bubble charged, as CycleModel does, to what the
// port did span_latency() cycles earlier (setup_load before that). The port's category is
// piecewise constant over the decoder's items and waits, recorded as segments.
class BreakdownRecorder {
 public:
  BreakdownRecorder(const CycleConfig& unit, int span_latency)
      : shift_(span_latency),
        busy_from_(unit.slot.interval > 1 ? 1 : unit.slot.latency + 1),
        busy_to_(unit.slot.latency + 2) {}

  // From cycle `from` on, the port does `category`'s work (until the next call).
  void port(Cycle from, CycleModel::Category category) {
    if (port_.empty() || port_.back().second != category)
      port_.push_back({from, category});  // else it goes on
  }
  // A span's first and last emit.
  void span(Cycle first, Cycle last) {
    const Cycle b = first + busy_from_, e = last + busy_to_;  // [b, e)
    if (!busy_.empty() && b <= busy_.back().second)
      busy_.back().second = std::max(busy_.back().second, e);
    else
      busy_.push_back({b, e});
  }

  // beats: the pixel beats that left (pixels with one lane).
  CycleBreakdown finish(Cycle total, uint64_t beats) {
    CycleBreakdown b;
    uint64_t busy = 0;
    for (const auto& iv : busy_) busy += static_cast<uint64_t>(iv.second - iv.first);
    b.pixel = beats;
    b.unit_stall = busy - beats;
    // Bubbles in [from, to): the cycles there outside every busy interval.
    size_t j = 0;
    uint64_t below = 0;  // busy cycles in the intervals before j
    const auto busy_below = [&](Cycle x) {
      while (j < busy_.size() && busy_[j].second <= x)
        below += static_cast<uint64_t>(busy_[j].second - busy_[j].first), ++j;
      return below + (j < busy_.size() && busy_[j].first < x
                          ? static_cast<uint64_t>(x - busy_[j].first)
                          : 0);
    };
    const auto charge = [&](CycleModel::Category c, Cycle from, Cycle to) {
      from = std::clamp<Cycle>(from, 0, total);
      to = std::clamp<Cycle>(to, from, total);
      const uint64_t bubbles =
          static_cast<uint64_t>(to - from) - (busy_below(to) - busy_below(from));
      switch (c) {
        case CycleModel::Category::kCommandGap:
          b.command_gap += bubbles;
          break;
        case CycleModel::Category::kMaterial:
          b.material += bubbles;
          break;
        case CycleModel::Category::kTable:
          b.table += bubbles;
          break;
        case CycleModel::Category::kCommandWords:
          b.command_words += bubbles;
          break;
        default:
          b.setup_load += bubbles;
          break;
      }
    };
    charge(CycleModel::Category::kSetupLoad, 0, shift_);
    for (size_t i = 0; i < port_.size(); ++i) {
      const Cycle to = i + 1 < port_.size() ? port_[i + 1].first : total;
      charge(port_[i].second, port_[i].first + shift_, to + shift_);
    }
    return b;
  }

 private:
  Cycle shift_, busy_from_, busy_to_;
  std::vector<std::pair<Cycle, CycleModel::Category>> port_;
  std::vector<std::pair<Cycle, Cycle>> busy_;
};

CycleModel::Category header_category(Opcode op) {
  switch (op) {
    case Opcode::kMaterial:
      return CycleModel::Category::kMaterial;
    case Opcode::kTable:
      return CycleModel::Category::kTable;
    case Opcode::kSpan:
      return CycleModel::Category::kSetupLoad;
    default:
      return CycleModel::Category::kCommandWords;
  }
}

std::string at_word(uint64_t i) { return "CycleEstimate: word " + std::to_string(i) + ": "; }

}  // namespace

CycleEstimate::CycleEstimate(CycleConfig unit)
    : unit_(unit), span_latency_(CycleModel(unit).span_latency()) {}

CycleEstimateRun CycleEstimate::run(const std::vector<uint64_t>& words, bool with_breakdown) const {
  std::optional<BreakdownRecorder> rec;
  if (with_breakdown) rec.emplace(unit_, span_latency_);
  uint64_t pixel_beats = 0;  // beats that leave the engines (CycleBreakdown::pixel)
  const uint64_t port = static_cast<uint64_t>(unit_.port_words);
  const int port_shift = port == 8 ? 3 : port == 4 ? 2 : port == 2 ? 1 : 0;
  const bool queued = unit_.tri_queue > 1;
  const bool host = unit_.host_setup;
  const uint64_t start_words = static_cast<uint64_t>(unit_.start_words);
  const size_t queue_size = static_cast<size_t>(unit_.span_queue());
  const Cycle interval = unit_.slot.interval;

  CycleEstimateRun r;
  r.words = words.size();
  r.beats = (words.size() + port - 1) / port;
  const uint64_t padded = r.beats * port;  // the last beat is padded with NOP words
  const auto word_at = [&](uint64_t i) { return CommandWord{i < words.size() ? words[i] : 0}; };
  const uint64_t in_beat = port - 1;  // port_words is a power of two
  const auto beat_end = [&](uint64_t i) { return (i | in_beat) + 1; };
  const auto next_bank = [&](int bank) { return bank + 1 == unit_.tri_queue ? 0 : bank + 1; };

  SpanPipe pipe(unit_);
  // Per coefficient bank: the cycle its last queued span entered s1.
  std::vector<Cycle> bank_free(static_cast<size_t>(unit_.tri_queue), kLongAgo);
  int wr_bank = 0;
  // Two material buffers: the bank the latest MATERIAL writes, and per bank the cycle the last
  // pixel of its latest span leaves the slot (spans leave in order).
  const bool mat_banked = unit_.material_buffers == 2;
  int mat_wr = 0;
  std::array<Cycle, 2> mat_leave = {kLongAgo, kLongAgo};
  TriangleCost* tri = nullptr;  // the latest TRIANGLE's: its SPANs follow it
  // Host setup: the span's part once its start values are all in (cycle `done`).
  const auto add_span = [&](const CommandWord& s, Cycle done, uint64_t at) {
    const uint64_t len = static_cast<uint64_t>(s.span_length());
    if (len == 0) throw std::invalid_argument(at_word(at) + "SPAN of length 0 (lengths are >= 1)");
    const Cycle leave = host ? pipe.add_host(done, len) : pipe.add(done, len);
    mat_leave[static_cast<size_t>(mat_wr)] = leave;
    if (rec) rec->span(pipe.first_emit(), pipe.last_emit());
    if (queued) bank_free[static_cast<size_t>(wr_bank)] = pipe.last_entry();
    r.pixels += len;
    pixel_beats += beats(len, static_cast<uint64_t>(unit_.lanes));
    if (s.span_last())
      r.scanlines.push_back(
          {s.span_y(), static_cast<uint64_t>(leave), s.span_x0() + s.span_length() - 1});
    if (tri) {
      ++tri->spans;
      tri->pixels += len;
      tri->engine_cycles +=
          beats(len, static_cast<uint64_t>(unit_.lanes)) * static_cast<uint64_t>(interval);
    }
  };

  // The first cycle on which a header of this opcode may go (model/command_stream.h).
  const auto ready = [&](const CommandWord& word) -> Cycle {
    switch (static_cast<Opcode>(word.opcode())) {
      case Opcode::kSpan:
        // Host setup: a free start bank entry. Without a queue: s1 free. With one: room, i.e.
        // the span queue_size places earlier has entered s1.
        if (host) return pipe.start_entry_free();
        if (!queued) return pipe.s1_free();
        return pipe.spans() >= queue_size ? pipe.entry(pipe.spans() - queue_size) + 1 : 0;
      case Opcode::kTriangle: {
        // A free bank: the last span queued with the bank it loads has entered s1.
        if (!queued) return 0;
        return bank_free[static_cast<size_t>(next_bank(wr_bank))] + 1;
      }
      case Opcode::kMaterial:
        // Two buffers: no span of the bank it switches to in flight.
        if (mat_banked) return mat_leave[static_cast<size_t>(1 - mat_wr)];
        return pipe.empty();
      case Opcode::kTable:
        // Two buffers, a per-material table: no span of the latest MATERIAL's bank in flight.
        if (mat_banked && word.table_per_material()) return mat_leave[static_cast<size_t>(mat_wr)];
        return pipe.empty();
      default:
        return 0;
    }
  };

  Cycle t = 0;           // earliest cycle of the next item
  Cycle last_item = -1;  // the cycle the last word was taken
  uint64_t w = 0;        // next word to take
  while (w < padded) {
    // ---- the header at w: it goes on the first cycle >= t on which it may ----
    const CommandWord word = word_at(w);
    const Opcode op = static_cast<Opcode>(word.opcode());
    const Cycle c = std::max(t, ready(word));
    if (rec) rec->port(t, header_category(op));  // waiting for it, then taking it
    last_item = c;
    t = c + 1;
    uint64_t payload = 0;      // words after the header item
    bool tri_payload = false;  // TRIANGLE coefficients or a host-setup SPAN's start values
    std::optional<CommandWord> host_span;  // its header, until its start values are all in
    uint64_t host_span_at = 0;
    switch (op) {
      case Opcode::kNop:
        w = beat_end(w);
        break;
      case Opcode::kTriangle: {
        const uint64_t count = word.count();
        const uint64_t with_header = std::min<uint64_t>(count, beat_end(w) - w - 1);
        r.triangles.push_back({});
        tri = &r.triangles.back();
        tri->index = static_cast<uint32_t>(r.triangles.size() - 1);
        tri->xo = word.tri_xo();
        tri->yo = word.tri_yo();
        tri->words = static_cast<uint32_t>(1 + count);
        tri->decoder_cycles = 1;
        w += 1 + with_header;
        payload = count - with_header;
        tri_payload = true;
        if (queued) wr_bank = next_bank(wr_bank);
        break;
      }
      case Opcode::kSpan: {
        if (host) {
          // Its start values: as many as follow it in the beat now, the rest as a tail.
          const uint64_t with_header = std::min<uint64_t>(start_words, beat_end(w) - w - 1);
          host_span = word;
          host_span_at = w;
          w += 1 + with_header;
          payload = start_words - with_header;
          tri_payload = true;
          if (payload == 0) add_span(word, c, host_span_at);
          break;
        }
        // With a queue, the SPAN headers right behind this one in the beat go too, as far as
        // the queue has room on this cycle.
        uint64_t n = 1;
        if (queued) {
          const uint64_t room = queue_size - pipe.queued_on(c);
          const uint64_t end = beat_end(w);
          while (n < room && w + n < end && word_at(w + n).is(Opcode::kSpan)) ++n;
        }
        for (uint64_t k = 0; k < n; ++k) add_span(word_at(w + k), c, w + k);
        if (tri) ++tri->decoder_cycles;
        w += n;
        break;
      }
      case Opcode::kMaterial:
      case Opcode::kTable:
        if (op == Opcode::kMaterial && mat_banked) mat_wr = 1 - mat_wr;
        w += 1;
        payload = word.count();
        break;
      default:
        w += 1;
        break;
    }
    if (w + payload > padded) {
      throw std::invalid_argument(at_word(w - 1) + "the command's payload runs " +
                                  std::to_string(w + payload - padded) +
                                  " word(s) past the end of the stream");
    }
    if (payload == 0) continue;
    if (!tri_payload) {
      // MATERIAL / TABLE payload: one word a cycle, never with a header.
      if (rec) rec->port(t, header_category(op));
      last_item = t + static_cast<Cycle>(payload) - 1;
      t = last_item + 1;
      w += payload;
      continue;
    }
    // Triangle coefficient words still due: the rest of this beat, then a beat a cycle; the
    // item of the last ones may carry the next header (the loop takes it with t = that cycle).
    const uint64_t first = std::min(payload, beat_end(w) - w);
    const uint64_t rest = payload - first;
    const Cycle items = 1 + static_cast<Cycle>((rest + in_beat) >> port_shift);
    if (tri) tri->decoder_cycles += static_cast<uint64_t>(items);
    if (rec) rec->port(t, CycleModel::Category::kCommandWords);
    const Cycle tail_cycle = t + items - 1;
    w += payload;
    last_item = tail_cycle;
    t = tail_cycle + 1;
    // A host-setup SPAN's start values are all in with its last tail.
    if (host_span) add_span(*host_span, tail_cycle, host_span_at);
    if ((w & in_beat) == 0 || w >= padded) continue;
    // A header follows the tail in its beat: it goes on the tail's cycle if it may and is ready.
    const CommandWord next = word_at(w);
    const Opcode nop = static_cast<Opcode>(next.opcode());
    // Without a queue a SPAN's setup reads the coefficients as it is taken: never with them.
    // (With host setup the start values are no coefficients: a SPAN may join them.)
    const bool joins = !(nop == Opcode::kSpan && !queued && !host) && ready(next) <= tail_cycle;
    if (joins) {
      // Take it on the tail's cycle: the header logic above runs with t = tail_cycle and the
      // item's cycle is already counted for this triangle.
      t = tail_cycle;
      if (nop == Opcode::kSpan && tri) --tri->decoder_cycles;  // same item, same triangle
    }
  }
  r.cycles =
      static_cast<uint64_t>(std::max(last_item + 1, pipe.spans() ? pipe.last_leave() + 1 : 0));
  if (rec) {
    rec->port(last_item + 1, CycleModel::Category::kCommandGap);  // no beat left to offer
    r.breakdown = rec->finish(static_cast<Cycle>(r.cycles), pixel_beats);
  }
  return r;
}

}  // namespace shadesim
