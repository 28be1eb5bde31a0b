// CycleModel: the shading unit's control, clock by clock, in plain C++ — the timing of
// rtl/shade_unit.sv without its datapath. Usable on its own (fast cycle estimates and a
// breakdown of where the cycles went: run_cycle_model in sim/harness/cycle_run.h) or in
// lockstep with the RTL (clock()), where every
// scanline's completion cycle must match exactly.
//
// It is the composition of one model class per control module of the RTL, under model/control/
// (and StartBank's timing in model/start_bank.h), each with the module's registers and
// next-state logic, clocked each cycle in the RTL's order (clock()):
//   CmdDecoder (cmd_decoder.sv)   beats taken apart one item per cycle, headers held back while
//                                 the part of the unit they change is busy
//     CmdPayload (cmd_payload.sv) its payload FSM (u_payload): which header's payload words are
//                                 due, and how many
//   SpanSource (span_source.sv)   the span intake: where the engines' next span comes from
//     SpanQueue (span_queue.sv)   tri_queue > 1: queued spans and the coefficient banks' use
//     SetupCtrl (setup_ctrl.sv)   span setup in the unit: the three stages' valid bits and spans
//     StartBank (start_bank.sv)   host span setup: spans waiting with their start values
//   MaterialBank (material_bank)  material_buffers 2: the banks' writer and spans in flight
//   EngineCtrl (engine_ctrl.sv)   the engines' span: run, pixels left, `lanes` per beat
//   SpecSlots (spec_slots.sv)     an iterative specular unit's busy count
//   SlotMeta (slot_meta.sv)       the beats beside the slot: a LATENCY-deep line, or one
//                                 pending beat for an iterative unit; a second one
//                                 (u_combine_meta) beside pixel_combine's combine_stages
//   OutReg (out_reg.sv)           the pix register, advance = !valid || ready; a beat is up to
//                                 `lanes` pixels of one span (lane j = pixel x + j)
// (Indented: instantiated inside the module above, and owned by its class.) Modules the
// configuration does not elaborate are not clocked (decided once, at construction).
// coef_bank.sv (inside span_source.sv) has no model class: it holds coefficients, which never
// hold a cycle back (which bank a TRIANGLE writes and when it may is span_queue's, the
// SPAN-after-TRIANGLE rule cmd_decoder's).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "model/command_word.h"
#include "model/control/beat_meta.h"
#include "model/control/cmd_decoder.h"
#include "model/control/engine_ctrl.h"
#include "model/control/material_bank.h"
#include "model/control/out_reg.h"
#include "model/control/slot_meta.h"
#include "model/control/span_queue.h"
#include "model/control/span_source.h"
#include "model/control/spec_slots.h"
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
  int start_depth = UnitConfig::kStartDepth;  // UnitConfig::start_depth (shade_unit START_DEPTH)
  // UnitConfig::combine_stages: advances a beat waits between the slot and the pix register.
  int combine_stages = 0;

  CycleConfig() = default;
  // A unit with the default structure around this slot.
  CycleConfig(SlotTiming s) : slot(s) {}  // NOLINT(google-explicit-constructor): a slot is a unit
  CycleConfig(SlotTiming s, int words, int queue = 1, int pixel_lanes = 1)
      : slot(s), port_words(words), tri_queue(queue), lanes(pixel_lanes) {}
  // Spans the span queue holds with tri_queue > 1 (none with 1).
  int span_queue() const { return tri_queue > 1 ? kSpansPerQueuedTriangle * tri_queue : 0; }
  static constexpr int kSpansPerQueuedTriangle = SpanQueue::kSpansPerTriangle;
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
  bool idle() const {
    return decoder_.idle() && datapath_empty() && combine_.empty() && !out_.valid();
  }

  // Cycles from a SPAN header's acceptance to its first pixel leaving, with nothing stalled
  // (a span queue adds its register; host span setup has no setup stages, and its payload
  // words, when they come later than the header, add theirs).
  int span_latency() const { return (host_ ? 3 : 5) + (queued_ ? 1 : 0) + latency_; }

  // A whole stream under a testbench's gaps and back-pressure: run_cycle_model
  // (sim/harness/cycle_run.h); with none, CycleEstimate (model/cycle_estimate.h).

 private:
  using Item = CmdDecoder::Item;
  // The decoder's *_i inputs (shade_unit.sv's wiring), read only for the header that waits on
  // them: a view of the modules' outputs before the edge.
  struct DecoderInputs {
    const CycleModel& unit;
    bool s1_free_o;  // setup_ctrl's, this cycle
    bool eng_load;   // engine_ctrl's load_o, this cycle

    bool datapath_empty() const { return unit.datapath_empty(); }
    bool mat_other_free() const { return unit.mat_.other_free(); }
    bool mat_cur_free() const { return unit.mat_.cur_free(); }
    bool sq_full() const { return unit.span_source_.sq_full(); }
    unsigned sq_room() const { return unit.span_source_.sq_room(); }
    bool s1_free() const { return s1_free_o; }
    bool tri_bank_free() const { return unit.span_source_.tri_bank_free(); }
    bool start_free() const { return unit.span_source_.start_free(eng_load); }
  };

  // shade_unit.sv's datapath_empty: no span queued, in setup (or in the start bank), in the
  // engines or in the slot.
  bool datapath_empty() const {
    return span_source_.sq_empty() && !span_source_.busy() && !engines_.run() && meta_.empty();
  }
  // What the command port does this cycle, as a bubble category (kSetupLoad for SPAN headers).
  // header: the cycle is about a header (taken, or waited for), not payload words.
  Category port_category(bool cmd_valid, bool header, CommandWord word) const;
  // Charges this cycle (needs the state before the edge) and records the port's category.
  Category charge_cycle(bool cmd_valid, const Item& item, bool pix_fire);

  // The configuration, fixed at construction: which modules the unit elaborates.
  int latency_ = 0;          // the specular slot's and the combine's stages
  bool queued_ = false;      // Queued: tri_queue > 1 (a span queue)
  bool host_ = false;        // Host: host span setup (a start bank, no setup stages, no queue)
  bool mat_banked_ = false;  // material_buffers 2: MaterialBank
  // The control modules, named as shade_unit.sv's instances.
  CmdDecoder decoder_;      // u_decoder
  SpanSource span_source_;  // u_span_source
  MaterialBank mat_;        // u_material_bank (its bank control: mat_banked_ only)
  EngineCtrl engines_;      // u_engine_ctrl
  SpecSlots slots_;         // u_slots (timing)
  SlotMeta meta_;           // u_slot_meta
  SlotMeta combine_;        // u_combine_meta: combine_stages deep, moving on every advance
  OutReg out_;              // u_out_reg
  // The command port's category on each of the last span_latency() cycles (ring), for bubbles;
  // history_pos_ is the slot of the current cycle (cycle mod size, kept without a division).
  std::vector<Category> port_history_;
  size_t history_pos_ = 0;
  bool track_categories_ = true;
};

std::string to_string(CycleModel::Category c);

// clock() and what it calls are inline: in lockstep co-simulation they run once per simulated
// cycle next to the RTL's eval, and inlining them into that loop removes the call and the
// packing of Edge into registers. clock() is always_inline: with the modules' classes nested as
// the RTL's (SpanSource, CmdPayload) GCC 12 sizes it past its single-function limit and calls it
// (callgrind on cycle_bench BM_CycleModel: 5 % more instructions that way).

inline CycleModel::Category CycleModel::port_category(bool cmd_valid, bool header,
                                                      CommandWord word) const {
  if (!cmd_valid) return Category::kCommandGap;
  if (!header) {
    switch (decoder_.payload()) {
      case CmdDecoder::Payload::kMaterial:
        return Category::kMaterial;
      case CmdDecoder::Payload::kTable:
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

// One clock: first every module's outputs before the edge, in the order their combinational
// paths run in shade_unit.sv (out_reg's advance -> the slots' busy -> engine_ctrl -> span_source
// (setup_ctrl -> span_queue) -> cmd_decoder), then the edge, module by module from the pix register
// back to the decoder: each reads its upstream module's registers as they were before the edge, so
// that order is the one that keeps them unclobbered.
[[gnu::always_inline]] inline CycleModel::Edge CycleModel::clock(bool cmd_valid,
                                                                 const uint64_t* beat,
                                                                 bool pix_ready) {
  // ---- before the edge
  const bool adv = out_.adv(pix_ready);
  const bool spec_busy = slots_.busy();
  const bool span_valid = span_source_.s3_valid(decoder_.span_pay());
  const EngineCtrl::Out eng = engines_.outputs(span_valid, adv, spec_busy);
  const SetupCtrl::Moves moves = span_source_.moves(eng.load);
  const bool sq_pop = span_source_.sq_pop(moves);
  const Item item = decoder_.decode(beat, DecoderInputs{*this, moves.s1_free, eng.load});
  const bool span_fire = cmd_valid && item.span_header();

  Edge e;
  e.cmd_ready = item.cmd_ready();
  e.cmd_fire = cmd_valid && e.cmd_ready;
  const BeatMeta& pix = out_.beat();
  e.pix_fire = pix.valid && pix_ready;
  e.pix_eor = pix.eor;
  e.pix_x = pix.x;
  e.pix_y = pix.y;
  e.pix_count = pix.count;
  if (track_categories_) e.category = charge_cycle(cmd_valid, item, e.pix_fire);

  // ---- the edge
  const int mat_wr = mat_.wr_bank();  // the latest MATERIAL's bank, before the edge
  const BeatMeta from_engines = engines_.beat(eng, mat_.eng_bank());
  const bool out_adv = meta_.out_adv(adv, spec_busy);
  const BeatMeta& slot_out = meta_.out(from_engines);
  // The beat leaving the slot (it has read its material) enters the combine's line.
  const bool load_pix = out_adv && slot_out.valid;
  BeatMeta slot_beat = slot_out;
  slot_beat.valid = load_pix;
  if (mat_banked_) {
    // A span's last beat out of the slot: the pix register holds finished colours, which no
    // later MATERIAL changes. A span enters setup stage 1 from the span queue, or straight
    // from the decoder in the latest MATERIAL's bank; with host setup the engines load the
    // start bank's oldest (s1_bank_i: span_source's s1_mat_o).
    mat_.clock(cmd_valid && item.mat_header(), span_fire, host_ ? 1 : static_cast<int>(item.hdr_n),
               span_source_.s1_load(sq_pop, span_fire), span_source_.s1_mat(mat_wr), moves.s1_move,
               moves.s2_move, eng.load, load_pix && slot_out.span_end, slot_out.mat);
  }
  const BeatMeta& pix_in = combine_.out(slot_beat);
  out_.clock(adv, pix_in.valid, pix_in);  // before the lines move: pix_in may be an entry
  combine_.clock(adv, slot_beat);
  meta_.clock(out_adv, from_engines);
  slots_.clock(eng.emit);
  engines_.clock(eng, span_source_.s3_span());
  span_source_.clock(moves, sq_pop, eng.load, span_fire, cmd_valid && item.tri_header(), beat,
                     item.word, item.hdr_pos, item.hdr_n, mat_wr);
  decoder_.clock(cmd_valid, item);
  return e;
}

inline CycleModel::Category CycleModel::charge_cycle(bool cmd_valid, const Item& item,
                                                     bool pix_fire) {
  const size_t slot = history_pos_;
  Category category = port_history_[slot];  // the port's category span_latency() cycles ago
  if (pix_fire) {
    category = Category::kPixel;
  } else if (out_.valid()) {
    category = Category::kBackPressure;
  } else if (slots_.iterative() && !(meta_.empty() && combine_.empty())) {
    category = Category::kUnitStall;  // the pix register is empty, the unit holds a beat
  }
  port_history_[slot] =
      port_category(cmd_valid, item.take_hdr || !decoder_.in_payload(), item.word);
  if (++history_pos_ == port_history_.size()) history_pos_ = 0;
  return category;
}

}  // namespace shadesim
