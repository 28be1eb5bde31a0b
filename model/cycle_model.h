// CycleModel: the shading unit's control, clock by clock, in plain C++ — the timing of
// rtl/shade_unit.sv without its datapath. Usable on its own (fast cycle estimates and a
// breakdown of where the cycles went: run_cycle_model in sim/harness/cycle_run.h) or in
// lockstep with the RTL (clock()), where every
// scanline's completion cycle must match exactly.
//
// Mirrored structure (names as in the RTL): a command decoder (a beat of port_words words taken
// apart one item per cycle, model/command_stream.h; headers, payload counting; MATERIAL and TABLE
// wait for an empty datapath - with material_buffers 2 a MATERIAL waits only until no span of
// the material bank it switches to is in flight, and a per-material TABLE until no span of the
// latest MATERIAL's bank is: spans carry their material bank to the pix register, counted per
// bank), with tri_queue > 1 a span queue whose spans carry their
// triangle's coefficient bank (a TRIANGLE waits until no queued span reads the bank it
// loads), three span-setup stages s1..s3 with valid bits, the
// engines' run state (run, rem: pixels left, `lanes` of them per beat), the specular slot's timing
// (a LATENCY-deep delay line for a pipelined unit, one in-flight pixel and a busy count for an
// iterative one), and the pix output register with advance = !valid || ready. The pix register
// holds a beat: up to `lanes` pixels of one span (lane j = pixel x + j), one beat per cycle at
// most.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "model/command_word.h"
#include "model/specular_config.h"
#include "model/unit_config.h"

namespace shadesim {

// Timing of the specular slot between the engines and the pix register.
struct SlotTiming {
  int latency = 0;   // registers from the engines' values to the specular result
  int interval = 1;  // cycles per pixel; > 1: iterative unit (then latency == interval)

  // The selected unit's timing (its row in model/specular_units.cpp: ExponentLut /
  // SchlickDivider / WpowUnit latency and cycles_per_pixel; ideal: 0 and 1), as
  // rtl/specular_unit.sv builds it.
  static SlotTiming of(const SpecularConfig& config);
};

// Everything the cycle model needs of a unit: its slot timing and its throughput structure
// (the control the RTL builds from UnitConfig; the datapath widths do not matter here).
struct CycleConfig {
  SlotTiming slot;
  int port_words = 1;        // UnitConfig::port_words
  int tri_queue = 1;         // UnitConfig::tri_queue
  int lanes = 1;             // UnitConfig::lanes: pixels per beat
  int material_buffers = 1;  // UnitConfig::material_buffers
  // Host span setup (UnitConfig::span_setup kHost): each SPAN header brings start_words payload
  // words (StartLayout::words) into the start bank of start_depth entries, which the engines load
  // from; there are no setup stages and no coefficient banks (tri_queue is 1).
  bool host_setup = false;
  int start_words = 0;
  int start_depth = kStartDepth;
  // A host-setup unit's start bank entries (shade_unit START_DEPTH, from rtl_parameters.cpp):
  // two, so the next span's words stream in while one span waits and one runs. Measured with
  // this model on the shipped scenes' own units: one entry gives specular 1.233, torus 1.133,
  // suzanne 1.176 cycles/px, two 1.001 each; more than two do not help multi (1.205 at two,
  // 1.201 at eight), whose many short spans are bound by the 13 words each needs.
  static constexpr int kStartDepth = 2;

  CycleConfig() = default;
  // A unit with the default structure around this slot.
  CycleConfig(SlotTiming s) : slot(s) {}  // NOLINT(google-explicit-constructor): a slot is a unit
  CycleConfig(SlotTiming s, int words, int queue = 1, int pixel_lanes = 1)
      : slot(s), port_words(words), tri_queue(queue), lanes(pixel_lanes) {}
  // Spans the span queue holds with tri_queue > 1 (none with 1).
  int span_queue() const { return tri_queue > 1 ? kSpansPerQueuedTriangle * tri_queue : 0; }
  static constexpr int kSpansPerQueuedTriangle = 4;
  static CycleConfig of(const UnitConfig& config);
};

// Where a scanline ends: the cycle on which its end-of-row pixel (the beat holding it) leaves the
// unit.
struct ScanlineDone {
  int y = 0;
  uint64_t cycle = 0;
  int x = -1;  // x of the end-of-row pixel, when known
};

// Why a cycle passed. Every cycle is charged to exactly one category, so the counts partition
// the run's cycles. In priority order:
//   pixel          a pixel beat left the unit (pix_valid and pix_ready; 1..lanes pixels)
//   back_pressure  a beat waited in the pix register and pix_ready was low
//   unit_stall     the pix register was empty and an iterative specular unit held a pixel
//                  (computing it, or finished on this very cycle): its interval and latency
//   otherwise the unit had no pixel to give: a bubble. The engines starve only when a SPAN
//   header was not accepted early enough, so the bubble is charged to what the command port
//   was doing on the cycle that SPAN header would have had to be accepted for its pixel to
//   leave now, i.e. span_latency() cycles earlier:
//   command_gap    no word was offered (an idle gap in the input)
//   material       a MATERIAL header (waiting for the empty datapath - with two material
//                  buffers for its bank's last span to leave the slot - or accepted) or its
//                  payload: the drain, the words, and the refill after them
//   table          a TABLE header or payload word
//   command_words  TRIANGLE, a SPAN's start values (host span setup), END_FRAME or unknown
//                  words (command bandwidth)
//   setup_load     a SPAN header was offered then (or the run had not been going that long):
//                  the span's setup and engine-load latency was not hidden - the first span's
//                  fill, or the schedule shifted by back-pressure / unit stalls
struct CycleBreakdown {
  uint64_t pixel = 0;
  uint64_t back_pressure = 0;
  uint64_t unit_stall = 0;
  uint64_t command_gap = 0;
  uint64_t material = 0;
  uint64_t table = 0;
  uint64_t command_words = 0;
  uint64_t setup_load = 0;

  struct Row {
    const char* name;
    uint64_t cycles;
    const char* meaning;
  };
  // In the order above, for printing and JSON; the cycles sum to total().
  std::vector<Row> rows() const;
  uint64_t total() const;
};

struct CycleRun {
  uint64_t cycles = 0;  // cycles until every beat is accepted and every pixel has left
  uint64_t pixels = 0;  // pixels, not beats (the breakdown's `pixel` row counts beats)
  uint64_t words = 0;
  uint64_t beats = 0;
  CycleBreakdown breakdown;  // partitions `cycles`
  std::vector<ScanlineDone> scanlines;
};

class CycleModel {
 public:
  // The category a cycle is charged to (see CycleBreakdown).
  enum class Category : uint8_t {
    kPixel,
    kBackPressure,
    kUnitStall,
    kCommandGap,
    kMaterial,
    kTable,
    kCommandWords,
    kSetupLoad
  };

  // What happened on one clock edge.
  struct Edge {
    bool cmd_ready = false;    // combinational, before the edge
    bool cmd_fire = false;     // the beat on the port was accepted on this edge
    bool pix_fire = false;     // a pixel beat left on this edge
    bool pix_eor = false;      // ... holding its span's end-of-row pixel (its last)
    int pix_x = 0, pix_y = 0;  // lane 0's pixel
    int pix_count = 0;         // pixels in the beat: lanes 0 .. pix_count-1 valid
    Category category = Category::kSetupLoad;
  };

  // Throws std::invalid_argument for a negative latency, an interval < 1, an iterative
  // interval that differs from the latency, a port width other than 1, 2, 4, 8, or lanes other
  // than 1, 2, 4, or material_buffers other than 1, 2.
  explicit CycleModel(CycleConfig timing = CycleConfig{});

  // Inputs as seen just before the edge (`beat`: the port_words words on the port); advances
  // the state by one clock.
  Edge clock(bool cmd_valid, const uint64_t* beat, bool pix_ready);
  // A one-word port.
  Edge clock(bool cmd_valid, uint64_t cmd_word, bool pix_ready) {
    return clock(cmd_valid, &cmd_word, pix_ready);
  }

  // Whether clock() charges each cycle to a category (Edge::category, kept by default). A
  // caller that only follows the cycles - the co-simulation's lockstep block - turns it off;
  // nothing else in an Edge changes.
  void track_categories(bool on) { track_categories_ = on; }

  // Nothing in flight, no pixel waiting, and no beat half taken apart.
  bool idle() const { return !in_payload_ && pos_ == 0 && datapath_empty() && !pix_.valid; }

  // Cycles from a SPAN header's acceptance to its first pixel leaving, with nothing stalled
  // (a span queue adds its register; host span setup has no setup stages, and its payload
  // words, when they come later than the header, add theirs).
  int span_latency() const { return (host_ ? 3 : 5) + (queued() ? 1 : 0) + timing_.latency; }

  // A whole stream under a testbench's gaps and back-pressure: run_cycle_model
  // (sim/harness/cycle_run.h); with none, CycleEstimate (model/cycle_estimate.h).

 private:
  struct Span {
    bool valid = false;
    int y = 0, x0 = 0, len = 0;
    bool last = false;
    int mat = 0;  // material bank (material_buffers 2)
  };
  struct Pix {
    bool valid = false;
    int x = 0, y = 0;  // lane 0's pixel
    bool eor = false;
    int count = 0;          // valid lanes
    int mat = 0;            // material bank of its span
    bool span_end = false;  // the span's last beat: its bank's count drops when it leaves the slot
  };
  enum class Payload { kSkip, kMaterial, kTriangle, kTable, kSpan };

  bool iterative() const { return timing_.interval > 1; }
  bool queued() const { return tri_queue_ > 1; }
  bool slot_empty() const;
  bool datapath_empty() const {
    return sq_count_ == 0 && sb_count_ == 0 && !s_[0].valid && !s_[1].valid && !s_[2].valid &&
           !run_ && slot_empty();
  }
  // What the command port does this cycle, as a bubble category (kSetupLoad for SPAN headers).
  // header: the cycle is about a header (taken, or waited for), not payload words.
  Category port_category(bool cmd_valid, bool header, CommandWord word) const;

  // The control's handshakes on this cycle: combinational, from the state before the edge, with
  // the RTL's equations.
  struct Flow {
    bool adv = false;       // the pix register takes the slot's output (!pix.valid || pix_ready)
    bool busy = false;      // an iterative slot still computes its pixel
    bool emit = false;      // the engines give a beat to the slot
    bool last_pix = false;  // the engines' beat is their span's last
    bool load_eng = false;  // the engines load the next span (setup stage 3 or the start bank)
    bool s2_move = false;   // setup stage 2 moves to stage 3
    bool s1_move = false;   // setup stage 1 moves to stage 2
    bool s1_free = false;   // setup stage 1 can take a span
    bool sq_pop = false;    // setup stage 1 takes the span queue's head
    int next_bank = 0;      // the coefficient bank the next TRIANGLE loads
  };
  // The item the decoder takes from the beat on the port this cycle (model/command_stream.h):
  // the triangle coefficient words due in the beat (tail), then at most one header (a
  // TRIANGLE's with its coefficient words after it in the beat), or one MATERIAL / TABLE
  // payload word; n words from pos_. Taken on the edge only when cmd_valid.
  struct Item {
    // Coefficient words of a TRIANGLE, or start values of a SPAN (host setup), are due: these
    // come as a tail per beat.
    bool tri_payload = false;
    unsigned tail = 0;      // such words taken before the header
    unsigned hdr_pos = 0;   // the header's word in the beat
    bool hdr_here = false;  // a header is in the beat
    CommandWord word;       // the header, or the payload word at pos_ without one
    Opcode op = Opcode::kNop;
    bool host_span = false;  // a host-setup SPAN header: its payload is its start values
    unsigned count = 0;      // the header's payload words
    unsigned hdr_n = 1;      // words taken with the header
    bool take_hdr = false;   // the header is here and ready
    unsigned n = 0;          // words taken
    bool beat_done = false;  // ... the rest of the beat

    bool span_header() const { return take_hdr && op == Opcode::kSpan; }
  };

  Flow handshakes(bool pix_ready) const;
  Item decode(const uint64_t* beat, const Flow& flow) const;
  unsigned header_words(const uint64_t* beat, const Item& item) const;
  bool header_ready(const Item& item, const Flow& flow) const;
  // Charges this cycle (needs the state before the edge) and records the port's category.
  Category charge_cycle(bool cmd_valid, const Item& item, bool pix_fire);
  // The edge, stage by stage from the pix register back to the decoder: each stage reads the
  // state of the stage upstream of it as it was before the edge, so clock() keeps this order.
  void clock_slot(const Flow& flow);
  bool clock_iterative_slot(const Flow& flow, const Pix& from_engines);
  bool clock_pipelined_slot(bool adv, const Pix& from_engines);
  void clock_engines(const Flow& flow);
  void clock_setup_stages(const Flow& flow);
  void clock_span_intake(const uint64_t* beat, const Item& item, const Flow& flow, bool span_fire);
  void clock_start_bank(CommandWord header, bool load_eng, bool span_fire);
  void clock_span_queue(const uint64_t* beat, const Item& item, bool sq_pop, bool s1_move,
                        bool span_fire);
  // A SPAN header's span, in the bank the latest MATERIAL writes.
  Span span_of(CommandWord header) const {
    const int y = header.span_y(), x0 = header.span_x0(), len = header.span_length();
    return Span{true, y, x0, len, header.span_last(), mat_wr_};
  }
  void take_item(const Item& item, int next_bank);
  void start_payload(const Item& item, int next_bank);
  // A TRIANGLE or host-setup SPAN: the payload words that came with the header are taken.
  void start_tail_payload(Payload op, const Item& item);
  void advance_payload(unsigned taken);

  SlotTiming timing_;
  unsigned port_words_ = 1;
  int tri_queue_ = 1;
  unsigned lanes_ = 1;
  // Host span setup: the start bank, a ring of sb_.size() entries, sb_count_ of them from
  // sb_head_ (the newest still filling while its SPAN's payload words come).
  bool host_ = false;
  unsigned start_words_ = 0;
  std::vector<Span> sb_;
  size_t sb_head_ = 0, sb_count_ = 0;
  // Triangle queue (tri_queue > 1): the span queue (a ring of sq_.size(), sq_count_ entries from
  // sq_head_), each span with the coefficient bank of its triangle; spans queued per bank; the
  // bank the latest TRIANGLE loads.
  struct QueuedSpan {
    Span span;
    int bank = 0;
  };
  std::vector<QueuedSpan> sq_;
  size_t sq_head_ = 0, sq_count_ = 0;
  std::vector<int> bank_spans_;
  int wr_bank_ = 0;
  // Material buffers (material_buffers 2): the bank the latest MATERIAL writes, and per bank the
  // spans taken and not yet out of the slot (all of them in flight with one buffer).
  bool mat_banked_ = false;
  int mat_wr_ = 0;
  int mat_spans_[2] = {0, 0};
  int mat_ = 0;  // the engines' span's bank
  // Decoder: pos_ is the next word of the beat on the port still to be taken.
  unsigned pos_ = 0;
  bool in_payload_ = false;
  Payload pay_op_ = Payload::kSkip;
  unsigned pay_idx_ = 0, pay_rem_ = 1;  // pay_rem_: payload words still to come
  // Span setup stages 1..3
  Span s_[3];
  // Engines: rem_ pixels of the span still to leave them, lanes_ per beat
  bool run_ = false;
  unsigned rem_ = 0;
  int x_ = 0, y_ = 0;
  bool last_ = false;
  // Specular slot: delay line (pipelined; dl_[latency-1] feeds the pix register) or the one
  // in-flight pixel and the cycles it stays busy (iterative).
  std::vector<Pix> dl_;
  Pix inflight_;
  int busy_ = 0;
  // Output register
  Pix pix_;
  // The command port's category on each of the last span_latency() cycles (ring), for bubbles;
  // history_pos_ is the slot of the current cycle (cycle mod size, kept without a division).
  std::vector<Category> port_history_;
  size_t history_pos_ = 0;
  bool track_categories_ = true;
};

std::string to_string(CycleModel::Category c);

// clock() and what it calls are inline: in lockstep co-simulation they run once per simulated
// cycle next to the RTL's eval, and inlining them into that loop removes the call and the
// packing of Edge into registers.

inline bool CycleModel::slot_empty() const {
  if (iterative()) return !inflight_.valid;
  for (const Pix& p : dl_) {
    if (p.valid) return false;
  }
  return true;
}

inline CycleModel::Category CycleModel::port_category(bool cmd_valid, bool header,
                                                      CommandWord word) const {
  if (!cmd_valid) return Category::kCommandGap;
  if (!header) {
    switch (pay_op_) {
      case Payload::kMaterial:
        return Category::kMaterial;
      case Payload::kTable:
        return Category::kTable;
      default:
        return Category::kCommandWords;
    }
  }
  switch (static_cast<Opcode>(word.opcode())) {
    case Opcode::kMaterial:
      return Category::kMaterial;
    case Opcode::kTable:
      return Category::kTable;
    case Opcode::kSpan:
      return Category::kSetupLoad;
    default:
      return Category::kCommandWords;
  }
}

inline CycleModel::Edge CycleModel::clock(bool cmd_valid, const uint64_t* beat, bool pix_ready) {
  const Flow flow = handshakes(pix_ready);
  const Item item = decode(beat, flow);
  Edge e;
  e.cmd_ready = item.n > 0 && item.beat_done;
  e.cmd_fire = cmd_valid && e.cmd_ready;
  e.pix_fire = pix_.valid && pix_ready;
  e.pix_eor = pix_.eor;
  e.pix_x = pix_.x;
  e.pix_y = pix_.y;
  e.pix_count = pix_.count;
  if (track_categories_) e.category = charge_cycle(cmd_valid, item, e.pix_fire);

  clock_slot(flow);
  clock_engines(flow);
  clock_setup_stages(flow);
  clock_span_intake(beat, item, flow, cmd_valid && item.span_header());
  if (cmd_valid) take_item(item, flow.next_bank);
  return e;
}

inline CycleModel::Flow CycleModel::handshakes(bool pix_ready) const {
  Flow f;
  f.adv = !pix_.valid || pix_ready;
  f.busy = busy_ > 0;
  f.emit = run_ && f.adv && !f.busy;
  // The span's last beat: 1 <= rem <= lanes (rem - 1 < lanes, as the RTL compares it).
  f.last_pix = rem_ - 1 < lanes_;
  // Host span setup: the engines load the start bank's oldest entry once its payload is in.
  const bool sb_filling = in_payload_ && pay_op_ == Payload::kSpan;
  const bool sb_ready = sb_count_ > (sb_filling ? 1u : 0u);
  f.load_eng = (host_ ? sb_ready : s_[2].valid) && (!run_ || (f.emit && f.last_pix));
  const bool s3_free = !s_[2].valid || f.load_eng;
  f.s2_move = s_[1].valid && s3_free;
  f.s1_move = s_[0].valid && (!s_[1].valid || f.s2_move);
  f.s1_free = !s_[0].valid || f.s1_move;
  // With a triangle queue, span setup takes its spans from the span queue.
  f.sq_pop = queued() && sq_count_ > 0 && f.s1_free;
  f.next_bank = queued() ? (wr_bank_ + 1) % tri_queue_ : 0;
  return f;
}

inline CycleModel::Item CycleModel::decode(const uint64_t* beat, const Flow& flow) const {
  Item item;
  const unsigned beat_left = port_words_ - pos_;
  item.tri_payload = in_payload_ && (pay_op_ == Payload::kTriangle || pay_op_ == Payload::kSpan);
  item.tail = item.tri_payload ? std::min(pay_rem_, beat_left) : 0;
  item.hdr_pos = pos_ + item.tail;
  item.hdr_here =
      (!in_payload_ || (item.tri_payload && pay_rem_ <= beat_left)) && item.hdr_pos < port_words_;
  item.word = CommandWord{beat[item.hdr_here ? item.hdr_pos : pos_]};
  item.op = static_cast<Opcode>(item.word.opcode());
  // Payload words: the header's count, but a host-setup SPAN's count is its length.
  item.host_span = host_ && item.op == Opcode::kSpan;
  item.count = item.host_span ? start_words_ : item.word.count();
  item.hdr_n = header_words(beat, item);
  item.take_hdr = item.hdr_here && header_ready(item, flow);
  item.n =
      item.tail + (item.take_hdr ? item.hdr_n : 0) + (in_payload_ && !item.tri_payload ? 1 : 0);
  item.beat_done = item.n == beat_left;
  return item;
}

inline unsigned CycleModel::header_words(const uint64_t* beat, const Item& item) const {
  if (item.op == Opcode::kNop) return port_words_ - item.hdr_pos;
  if (item.op == Opcode::kTriangle || item.host_span)
    return 1 + std::min(item.count, port_words_ - item.hdr_pos - 1);
  if (item.op == Opcode::kSpan && queued() && item.hdr_here) {
    // A run of SPAN headers goes into the span queue together, as many as it has room for.
    const unsigned room = static_cast<unsigned>(sq_.size() - sq_count_);
    unsigned run = 1;
    while (item.hdr_pos + run < port_words_ &&
           CommandWord{beat[item.hdr_pos + run]}.is(Opcode::kSpan))
      ++run;
    return std::max(1u, std::min(run, room));
  }
  return 1;
}

inline bool CycleModel::header_ready(const Item& item, const Flow& flow) const {
  switch (item.op) {
    // Only MATERIAL and TABLE headers wait for the empty datapath; the check walks the delay
    // line. With two material buffers a MATERIAL waits only for the bank it switches to, and a
    // per-material TABLE (it writes the latest MATERIAL's bank only) for that bank.
    case Opcode::kMaterial:
      return mat_banked_ ? mat_spans_[1 - mat_wr_] == 0 : datapath_empty();
    case Opcode::kTable:
      return mat_banked_ && item.word.table_per_material() ? mat_spans_[mat_wr_] == 0
                                                           : datapath_empty();
    case Opcode::kSpan:
      // Host setup: a free start bank entry, or the oldest one leaving for the engines now.
      if (host_) return sb_count_ < sb_.size() || flow.load_eng;
      // Without a span queue a SPAN's setup reads the coefficients as it is taken: not on the
      // edge that writes its triangle's last words.
      return queued() ? sq_count_ < sq_.size() : flow.s1_free && item.tail == 0;
    case Opcode::kTriangle:
      // A TRIANGLE loads the next bank once no queued span needs that bank's coefficients.
      return !queued() || bank_spans_[static_cast<size_t>(flow.next_bank)] == 0;
    default:
      return true;
  }
}

inline CycleModel::Category CycleModel::charge_cycle(bool cmd_valid, const Item& item,
                                                     bool pix_fire) {
  const size_t slot = history_pos_;
  Category category = port_history_[slot];  // the port's category span_latency() cycles ago
  if (pix_fire) {
    category = Category::kPixel;
  } else if (pix_.valid) {
    category = Category::kBackPressure;
  } else if (iterative() && inflight_.valid) {
    category = Category::kUnitStall;
  }
  port_history_[slot] = port_category(cmd_valid, item.take_hdr || !in_payload_, item.word);
  if (++history_pos_ == port_history_.size()) history_pos_ = 0;
  return category;
}

inline void CycleModel::clock_slot(const Flow& flow) {
  const Pix from_engines{
      run_, x_,           y_, last_ && flow.last_pix, static_cast<int>(std::min(rem_, lanes_)),
      mat_, flow.last_pix};
  const bool to_pix = iterative() ? clock_iterative_slot(flow, from_engines)
                                  : clock_pipelined_slot(flow.adv, from_engines);
  // A span's last beat out of the slot: the pix register holds finished colours, which no
  // later MATERIAL changes.
  if (to_pix && pix_.valid && pix_.span_end) --mat_spans_[pix_.mat];
}

// Both return whether the pix register took the slot's output.
inline bool CycleModel::clock_iterative_slot(const Flow& flow, const Pix& from_engines) {
  bool to_pix = false;
  if (flow.adv && !flow.busy) {
    pix_ = inflight_;
    inflight_ = from_engines;  // valid == emit
    to_pix = true;
  } else if (flow.adv) {
    pix_.valid = false;
  }
  if (flow.emit)
    busy_ = timing_.interval - 1;
  else if (busy_ > 0)
    --busy_;
  return to_pix;
}

inline bool CycleModel::clock_pipelined_slot(bool adv, const Pix& from_engines) {
  if (!adv) return false;
  if (dl_.empty()) {
    pix_ = from_engines;
  } else {
    pix_ = dl_.back();
    for (size_t i = dl_.size() - 1; i > 0; --i) dl_[i] = dl_[i - 1];
    dl_[0] = from_engines;
  }
  return true;
}

inline void CycleModel::clock_engines(const Flow& flow) {
  if (flow.load_eng) {
    const Span& next = host_ ? sb_[sb_head_] : s_[2];
    run_ = true;
    rem_ = static_cast<unsigned>(next.len);
    x_ = next.x0;
    y_ = next.y;
    last_ = next.last;
    mat_ = next.mat;
  } else if (flow.emit) {
    if (flow.last_pix) run_ = false;
    rem_ -= lanes_;  // wraps after the last beat, as the RTL's rem_q; reloaded before use
    x_ += static_cast<int>(lanes_);
  }
}

inline void CycleModel::clock_setup_stages(const Flow& flow) {
  if (flow.s2_move)
    s_[2] = s_[1];
  else if (flow.load_eng)
    s_[2].valid = false;
  if (flow.s1_move)
    s_[1] = s_[0];
  else if (flow.s2_move)
    s_[1].valid = false;
}

// Where spans enter: the start bank (host setup), setup stage 1, or the span queue.
inline void CycleModel::clock_span_intake(const uint64_t* beat, const Item& item, const Flow& flow,
                                          bool span_fire) {
  if (host_) {
    clock_start_bank(item.word, flow.load_eng, span_fire);
    return;
  }
  if (span_fire) mat_spans_[mat_wr_] += static_cast<int>(item.hdr_n);
  if (queued()) {
    clock_span_queue(beat, item, flow.sq_pop, flow.s1_move, span_fire);
  } else if (span_fire) {
    s_[0] = span_of(item.word);
  } else if (flow.s1_move) {
    s_[0].valid = false;
  }
}

inline void CycleModel::clock_start_bank(CommandWord header, bool load_eng, bool span_fire) {
  if (load_eng) {
    if (++sb_head_ == sb_.size()) sb_head_ = 0;
    --sb_count_;
  }
  if (span_fire) {
    ++mat_spans_[mat_wr_];
    size_t newest = sb_head_ + sb_count_;
    if (newest >= sb_.size()) newest -= sb_.size();
    sb_[newest] = span_of(header);
    ++sb_count_;
  }
}

inline void CycleModel::clock_span_queue(const uint64_t* beat, const Item& item, bool sq_pop,
                                         bool s1_move, bool span_fire) {
  if (sq_pop) {
    const QueuedSpan& head = sq_[sq_head_];
    s_[0] = head.span;
    --bank_spans_[static_cast<size_t>(head.bank)];
    if (++sq_head_ == sq_.size()) sq_head_ = 0;
    --sq_count_;
  } else if (s1_move) {
    s_[0].valid = false;
  }
  if (!span_fire) return;
  for (unsigned k = 0; k < item.hdr_n; ++k) {
    size_t newest = sq_head_ + sq_count_;
    if (newest >= sq_.size()) newest -= sq_.size();
    sq_[newest] = {span_of(CommandWord{beat[item.hdr_pos + k]}), wr_bank_};
    ++bank_spans_[static_cast<size_t>(wr_bank_)];
    ++sq_count_;
  }
}

inline void CycleModel::take_item(const Item& item, int next_bank) {
  if (item.n > 0) pos_ = item.beat_done ? 0 : pos_ + item.n;
  if (item.take_hdr)
    start_payload(item, next_bank);
  else if (in_payload_)
    advance_payload(item.tri_payload ? item.tail : 1);
}

inline void CycleModel::start_payload(const Item& item, int next_bank) {
  pay_idx_ = 0;
  pay_rem_ = item.count;
  switch (item.op) {
    case Opcode::kMaterial:
      // Its payload writes the other bank, which no span in flight reads.
      if (mat_banked_) mat_wr_ = 1 - mat_wr_;
      pay_op_ = Payload::kMaterial;
      in_payload_ = item.count != 0;
      break;
    case Opcode::kTriangle:
      wr_bank_ = next_bank;
      start_tail_payload(Payload::kTriangle, item);
      break;
    case Opcode::kTable:
      pay_op_ = Payload::kTable;
      in_payload_ = item.count != 0;
      break;
    case Opcode::kSpan:
      if (host_) {
        start_tail_payload(Payload::kSpan, item);
      } else {
        pay_op_ = Payload::kSkip;
        in_payload_ = false;
      }
      break;
    default:
      pay_op_ = Payload::kSkip;
      in_payload_ = false;
      break;
  }
}

inline void CycleModel::start_tail_payload(Payload op, const Item& item) {
  pay_op_ = op;
  pay_idx_ = item.hdr_n - 1;
  pay_rem_ = (item.count - item.hdr_n + 1) & CommandWord::kFieldMask;
  in_payload_ = item.count > item.hdr_n - 1;
}

inline void CycleModel::advance_payload(unsigned taken) {
  if (taken == pay_rem_) in_payload_ = false;  // the payload's last word
  pay_idx_ = (pay_idx_ + taken) & CommandWord::kFieldMask;
  pay_rem_ = (pay_rem_ - taken) & CommandWord::kFieldMask;
}

}  // namespace shadesim
