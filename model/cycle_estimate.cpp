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
        combine_(unit.combine_stages),
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
  // The cycle the last pixel of the latest span leaves the unit: it left the slot on
  // last_leave() and waits combine_stages advances beside pixel_combine's registers.
  Cycle last_pix_leave() const { return last_leave_ + combine_; }
  // Earliest cycle on which s1 is free for the next span (unqueued decoder).
  Cycle s1_free() const { return prev_[1]; }
  // Earliest cycle on which the datapath is empty: the last pixel has left the slot (the
  // combine's registers hold values already read from the material).
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
  Cycle interval_, latency_, combine_;
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
// pixel or one leaving; each combine stage moves the end, and a pipelined slot's start, one
// cycle later); every other cycle is a bubble charged, as CycleModel does, to what the
// port did span_latency() cycles earlier (setup_load before that). The port's category is
// piecewise constant over the decoder's items and waits, recorded as segments.
class BreakdownRecorder {
 public:
  BreakdownRecorder(const CycleConfig& unit, int span_latency)
      : shift_(span_latency),
        busy_from_(unit.slot.interval > 1 ? 1 : unit.slot.latency + 1 + unit.combine_stages),
        busy_to_(unit.slot.latency + 2 + unit.combine_stages) {}

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

// One pass of CycleEstimate::run over a stream: the decoder's items header by header (each on
// the first cycle it may go), with the spans' pipe beside them.
class EstimateWalk {
 public:
  EstimateWalk(const CycleConfig& unit, int span_latency, const std::vector<uint64_t>& words,
               bool with_breakdown);
  CycleEstimateRun run();

 private:
  // What a header taken leaves for the items after it.
  struct Payload {
    uint64_t words = 0;  // words after the header item
    bool tail = false;   // TRIANGLE coefficients or a host-setup SPAN's start values: by beats
    std::optional<CommandWord> host_span;  // its header, until its start values are all in
    uint64_t host_span_at = 0;
  };

  CommandWord word_at(uint64_t i) const { return CommandWord{i < words_.size() ? words_[i] : 0}; }
  uint64_t beat_end(uint64_t i) const { return (i | in_beat_) + 1; }
  int next_bank(int bank) const { return bank + 1 == unit_.tri_queue ? 0 : bank + 1; }
  Cycle ready(const CommandWord& word) const;
  void add_span(const CommandWord& s, Cycle done, uint64_t at);
  Payload take_header(const CommandWord& word, Cycle c);
  Payload take_triangle(const CommandWord& word);
  Payload take_host_span(const CommandWord& word, Cycle c);
  void take_spans(const CommandWord& word, Cycle c);
  void check_payload_fits(uint64_t payload) const;
  void take_word_payload(Opcode op, uint64_t payload);
  void take_tail(const Payload& p);
  void join_next_header(Cycle tail_cycle);
  CycleEstimateRun finish();

  const CycleConfig& unit_;
  const std::vector<uint64_t>& words_;
  const uint64_t port_;
  const int port_shift_;
  const uint64_t in_beat_;  // port_words is a power of two
  const uint64_t padded_;   // the last beat is padded with NOP words
  const bool queued_;
  const bool host_;
  const uint64_t start_words_;
  const size_t queue_size_;
  const Cycle interval_;
  std::optional<BreakdownRecorder> rec_;
  uint64_t pixel_beats_ = 0;  // beats that leave the engines (CycleBreakdown::pixel)
  CycleEstimateRun r_;
  SpanPipe pipe_;
  // Per coefficient bank: the cycle its last queued span entered s1.
  std::vector<Cycle> bank_free_;
  int wr_bank_ = 0;
  // Two material buffers: the bank the latest MATERIAL writes, and per bank the cycle the last
  // pixel of its latest span leaves the slot (spans leave in order).
  const bool mat_banked_;
  int mat_wr_ = 0;
  std::array<Cycle, 2> mat_leave_ = {kLongAgo, kLongAgo};
  TriangleCost* tri_ = nullptr;  // the latest TRIANGLE's: its SPANs follow it
  Cycle t_ = 0;                  // earliest cycle of the next item
  Cycle last_item_ = -1;         // the cycle the last word was taken
  uint64_t w_ = 0;               // next word to take
};

EstimateWalk::EstimateWalk(const CycleConfig& unit, int span_latency,
                           const std::vector<uint64_t>& words, bool with_breakdown)
    : unit_(unit),
      words_(words),
      port_(static_cast<uint64_t>(unit.port_words)),
      port_shift_(port_ == 8   ? 3
                  : port_ == 4 ? 2
                  : port_ == 2 ? 1
                               : 0),
      in_beat_(port_ - 1),
      padded_((words.size() + port_ - 1) / port_ * port_),
      queued_(unit.tri_queue > 1),
      host_(unit.host_setup),
      start_words_(static_cast<uint64_t>(unit.start_words)),
      queue_size_(static_cast<size_t>(unit.span_queue())),
      interval_(unit.slot.interval),
      pipe_(unit),
      bank_free_(static_cast<size_t>(unit.tri_queue), kLongAgo),
      mat_banked_(unit.material_buffers == 2) {
  if (with_breakdown) rec_.emplace(unit, span_latency);
  r_.words = words.size();
  r_.beats = (words.size() + port_ - 1) / port_;
}

// The first cycle on which a header of this opcode may go (model/command_stream.h).
Cycle EstimateWalk::ready(const CommandWord& word) const {
  switch (static_cast<Opcode>(word.opcode())) {
    case Opcode::kSpan:
      // Host setup: a free start bank entry. Without a queue: s1 free. With one: room, i.e.
      // the span queue_size places earlier has entered s1.
      if (host_) return pipe_.start_entry_free();
      if (!queued_) return pipe_.s1_free();
      return pipe_.spans() >= queue_size_ ? pipe_.entry(pipe_.spans() - queue_size_) + 1 : 0;
    case Opcode::kTriangle: {
      // A free bank: the last span queued with the bank it loads has entered s1.
      if (!queued_) return 0;
      return bank_free_[static_cast<size_t>(next_bank(wr_bank_))] + 1;
    }
    case Opcode::kMaterial:
      // Two buffers: no span of the bank it switches to in flight.
      if (mat_banked_) return mat_leave_[static_cast<size_t>(1 - mat_wr_)];
      return pipe_.empty();
    case Opcode::kTable:
      // Two buffers, a per-material table: no span of the latest MATERIAL's bank in flight.
      if (mat_banked_ && word.table_per_material()) return mat_leave_[static_cast<size_t>(mat_wr_)];
      return pipe_.empty();
    default:
      return 0;
  }
}

// Host setup: the span's part once its start values are all in (cycle `done`).
void EstimateWalk::add_span(const CommandWord& s, Cycle done, uint64_t at) {
  const uint64_t len = static_cast<uint64_t>(s.span_length());
  if (len == 0) throw std::invalid_argument(at_word(at) + "SPAN of length 0 (lengths are >= 1)");
  const Cycle leave = host_ ? pipe_.add_host(done, len) : pipe_.add(done, len);
  mat_leave_[static_cast<size_t>(mat_wr_)] = leave;
  if (rec_) rec_->span(pipe_.first_emit(), pipe_.last_emit());
  if (queued_) bank_free_[static_cast<size_t>(wr_bank_)] = pipe_.last_entry();
  const uint64_t lanes = static_cast<uint64_t>(unit_.lanes);
  r_.pixels += len;
  pixel_beats_ += CycleEstimate::beats(len, lanes);
  if (s.span_last())
    r_.scanlines.push_back({s.span_y(), static_cast<uint64_t>(pipe_.last_pix_leave()),
                            s.span_x0() + s.span_length() - 1});
  if (tri_) {
    ++tri_->spans;
    tri_->pixels += len;
    tri_->engine_cycles += CycleEstimate::beats(len, lanes) * static_cast<uint64_t>(interval_);
  }
}

CycleEstimateRun EstimateWalk::run() {
  while (w_ < padded_) {
    // ---- the header at w: it goes on the first cycle >= t on which it may ----
    const CommandWord word = word_at(w_);
    const Opcode op = static_cast<Opcode>(word.opcode());
    const Cycle c = std::max(t_, ready(word));
    if (rec_) rec_->port(t_, header_category(op));  // waiting for it, then taking it
    last_item_ = c;
    t_ = c + 1;
    const Payload payload = take_header(word, c);
    check_payload_fits(payload.words);
    if (payload.words == 0) continue;
    if (payload.tail)
      take_tail(payload);
    else
      take_word_payload(op, payload.words);
  }
  return finish();
}

EstimateWalk::Payload EstimateWalk::take_header(const CommandWord& word, Cycle c) {
  Payload p;
  switch (static_cast<Opcode>(word.opcode())) {
    case Opcode::kNop:
      w_ = beat_end(w_);
      break;
    case Opcode::kTriangle:
      return take_triangle(word);
    case Opcode::kSpan:
      if (host_) return take_host_span(word, c);
      take_spans(word, c);
      break;
    case Opcode::kMaterial:
      if (mat_banked_) mat_wr_ = 1 - mat_wr_;
      w_ += 1;
      p.words = word.count();
      break;
    case Opcode::kTable:
      w_ += 1;
      p.words = word.count();
      break;
    default:
      w_ += 1;
      break;
  }
  return p;
}

EstimateWalk::Payload EstimateWalk::take_triangle(const CommandWord& word) {
  const uint64_t count = word.count();
  const uint64_t with_header = std::min<uint64_t>(count, beat_end(w_) - w_ - 1);
  r_.triangles.push_back({});
  tri_ = &r_.triangles.back();
  tri_->index = static_cast<uint32_t>(r_.triangles.size() - 1);
  tri_->xo = word.tri_xo();
  tri_->yo = word.tri_yo();
  tri_->words = static_cast<uint32_t>(1 + count);
  tri_->decoder_cycles = 1;
  w_ += 1 + with_header;
  if (queued_) wr_bank_ = next_bank(wr_bank_);
  Payload p;
  p.words = count - with_header;
  p.tail = true;
  return p;
}

// Its start values: as many as follow it in the beat now, the rest as a tail.
EstimateWalk::Payload EstimateWalk::take_host_span(const CommandWord& word, Cycle c) {
  const uint64_t with_header = std::min<uint64_t>(start_words_, beat_end(w_) - w_ - 1);
  Payload p;
  p.host_span = word;
  p.host_span_at = w_;
  w_ += 1 + with_header;
  p.words = start_words_ - with_header;
  p.tail = true;
  if (p.words == 0) add_span(word, c, p.host_span_at);
  return p;
}

// With a queue, the SPAN headers right behind this one in the beat go too, as far as the queue
// has room on this cycle.
void EstimateWalk::take_spans(const CommandWord& word, Cycle c) {
  uint64_t n = 1;
  if (queued_) {
    const uint64_t room = queue_size_ - pipe_.queued_on(c);
    const uint64_t end = beat_end(w_);
    while (n < room && w_ + n < end && word_at(w_ + n).is(Opcode::kSpan)) ++n;
  }
  for (uint64_t k = 0; k < n; ++k) add_span(word_at(w_ + k), c, w_ + k);
  if (tri_) ++tri_->decoder_cycles;
  w_ += n;
}

void EstimateWalk::check_payload_fits(uint64_t payload) const {
  if (w_ + payload > padded_) {
    throw std::invalid_argument(at_word(w_ - 1) + "the command's payload runs " +
                                std::to_string(w_ + payload - padded_) +
                                " word(s) past the end of the stream");
  }
}

// MATERIAL / TABLE payload: one word a cycle, never with a header.
void EstimateWalk::take_word_payload(Opcode op, uint64_t payload) {
  if (rec_) rec_->port(t_, header_category(op));
  last_item_ = t_ + static_cast<Cycle>(payload) - 1;
  t_ = last_item_ + 1;
  w_ += payload;
}

// Triangle coefficient words still due: the rest of this beat, then a beat a cycle; the item of
// the last ones may carry the next header.
void EstimateWalk::take_tail(const Payload& p) {
  const uint64_t first = std::min(p.words, beat_end(w_) - w_);
  const uint64_t rest = p.words - first;
  const Cycle items = 1 + static_cast<Cycle>((rest + in_beat_) >> port_shift_);
  if (tri_) tri_->decoder_cycles += static_cast<uint64_t>(items);
  if (rec_) rec_->port(t_, CycleModel::Category::kCommandWords);
  const Cycle tail_cycle = t_ + items - 1;
  w_ += p.words;
  last_item_ = tail_cycle;
  t_ = tail_cycle + 1;
  // A host-setup SPAN's start values are all in with its last tail.
  if (p.host_span) add_span(*p.host_span, tail_cycle, p.host_span_at);
  if ((w_ & in_beat_) == 0 || w_ >= padded_) return;
  join_next_header(tail_cycle);
}

// A header follows the tail in its beat: it goes on the tail's cycle if it may and is ready (the
// header loop then takes it with t = that cycle).
void EstimateWalk::join_next_header(Cycle tail_cycle) {
  const CommandWord next = word_at(w_);
  const Opcode op = static_cast<Opcode>(next.opcode());
  // Without a queue a SPAN's setup reads the coefficients as it is taken: never with them.
  // (With host setup the start values are no coefficients: a SPAN may join them.)
  const bool joins = !(op == Opcode::kSpan && !queued_ && !host_) && ready(next) <= tail_cycle;
  if (joins) {
    // Take it on the tail's cycle: the item's cycle is already counted for this triangle.
    t_ = tail_cycle;
    if (op == Opcode::kSpan && tri_) --tri_->decoder_cycles;  // same item, same triangle
  }
}

CycleEstimateRun EstimateWalk::finish() {
  r_.cycles = static_cast<uint64_t>(
      std::max(last_item_ + 1, pipe_.spans() ? pipe_.last_pix_leave() + 1 : 0));
  if (rec_) {
    rec_->port(last_item_ + 1, CycleModel::Category::kCommandGap);  // no beat left to offer
    r_.breakdown = rec_->finish(static_cast<Cycle>(r_.cycles), pixel_beats_);
  }
  return std::move(r_);
}

}  // namespace

CycleEstimate::CycleEstimate(CycleConfig unit)
    : unit_(unit), span_latency_(CycleModel(unit).span_latency()) {}

CycleEstimateRun CycleEstimate::run(const std::vector<uint64_t>& words, bool with_breakdown) const {
  return EstimateWalk(unit_, span_latency_, words, with_breakdown).run();
}

}  // namespace shadesim
