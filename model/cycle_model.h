// CycleModel: the shading unit's control, clock by clock, in plain C++ — the timing of
// rtl/shade_unit.sv without its datapath. Usable on its own (fast cycle estimates and a
// breakdown of where the cycles went: run()) or in lockstep with the RTL (clock()), where every
// scanline's completion cycle must match exactly.
//
// Mirrored structure (names as in the RTL): a command decoder (headers, payload counting;
// MATERIAL and TABLE wait for an empty datapath), three span-setup stages s1..s3 with valid bits, the
// engines' run state (run, rem), the specular slot's timing (a LATENCY-deep delay line for a
// pipelined unit, one in-flight pixel and a busy count for an iterative one), and the pix output
// register with advance = !valid || ready.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/specular_config.h"
#include "model/stimulus.h"

namespace shadesim {

// Timing of the specular slot between the engines and the pix register.
struct SlotTiming {
  int latency = 0;   // registers from the engines' values to the specular result
  int interval = 1;  // cycles per pixel; > 1: iterative unit (then latency == interval)

  // The selected unit's timing (ExponentLut / SchlickDivider / WpowUnit latency and
  // cycles_per_pixel; ideal: 0 and 1), as rtl/specular_slot.sv builds it.
  static SlotTiming of(const SpecularConfig& config);
};

// Where a scanline ends: the cycle on which its end-of-row pixel leaves the unit.
struct ScanlineDone {
  int y = 0;
  uint64_t cycle = 0;
  int x = -1;  // x of the end-of-row pixel, when known
};

// Why a cycle passed. Every cycle is charged to exactly one category, so the counts partition
// the run's cycles. In priority order:
//   pixel          a pixel left the unit (pix_valid and pix_ready)
//   back_pressure  a pixel waited in the pix register and pix_ready was low
//   unit_stall     the pix register was empty and an iterative specular unit held a pixel
//                  (computing it, or finished on this very cycle): its interval and latency
//   otherwise the unit had no pixel to give: a bubble. The engines starve only when a SPAN
//   header was not accepted early enough, so the bubble is charged to what the command port
//   was doing on the cycle that SPAN header would have had to be accepted for its pixel to
//   leave now, i.e. span_latency() cycles earlier:
//   command_gap    no word was offered (an idle gap in the input)
//   material       a MATERIAL header (waiting for the empty datapath, or accepted) or its
//                  payload: the drain, the words, and the refill after them
//   table          a TABLE header or payload word
//   command_words  TRIANGLE, END_FRAME or unknown words (command bandwidth)
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
  uint64_t cycles = 0;  // cycles until every word is accepted and every pixel has left
  uint64_t pixels = 0;
  uint64_t words = 0;
  CycleBreakdown breakdown;  // partitions `cycles`
  std::vector<ScanlineDone> scanlines;
};

class CycleModel {
 public:
  // The category a cycle is charged to (see CycleBreakdown).
  enum class Category : uint8_t {
    kPixel, kBackPressure, kUnitStall, kCommandGap, kMaterial, kTable, kCommandWords, kSetupLoad
  };

  // What happened on one clock edge.
  struct Edge {
    bool cmd_ready = false;  // combinational, before the edge
    bool cmd_fire = false;
    bool pix_fire = false;   // a pixel left on this edge
    bool pix_eor = false;
    int pix_x = 0, pix_y = 0;
    Category category = Category::kSetupLoad;
  };

  // Throws std::invalid_argument for a negative latency, an interval < 1, or an iterative
  // interval that differs from the latency.
  explicit CycleModel(SlotTiming timing = SlotTiming{});

  // Inputs as seen just before the edge; advances the state by one clock.
  Edge clock(bool cmd_valid, uint64_t cmd_word, bool pix_ready);

  // Nothing in flight and no pixel waiting.
  bool idle() const { return !in_payload_ && datapath_empty() && !pix_.valid; }

  // Cycles from a SPAN header's acceptance to its first pixel leaving, with nothing stalled.
  int span_latency() const { return 5 + timing_.latency; }

  // Runs a whole stream with the stimulus's gaps and back-pressure.
  static CycleRun run(const std::vector<uint64_t>& words, const Stimulus& stim,
                      SlotTiming timing = SlotTiming{});

 private:
  struct Span {
    bool valid = false;
    int y = 0, x0 = 0, len = 0;
    bool last = false;
  };
  struct Pix {
    bool valid = false;
    int x = 0, y = 0;
    bool eor = false;
  };
  enum class Payload { kSkip, kMaterial, kTriangle, kTable };

  bool iterative() const { return timing_.interval > 1; }
  bool slot_empty() const;
  bool datapath_empty() const { return !s_[0].valid && !s_[1].valid && !s_[2].valid && !run_ && slot_empty(); }
  // What the command port does this cycle, as a bubble category (kSetupLoad for SPAN headers).
  Category port_category(bool cmd_valid, unsigned op) const;

  SlotTiming timing_;
  // Decoder
  bool in_payload_ = false;
  Payload pay_op_ = Payload::kSkip;
  unsigned pay_idx_ = 0, pay_last_ = 0;
  // Span setup stages 1..3
  Span s_[3];
  // Engines
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
  // The command port's category on each of the last span_latency() cycles (ring), for bubbles.
  std::vector<Category> port_history_;
  uint64_t cycle_ = 0;
};

std::string to_string(CycleModel::Category c);

}  // namespace shadesim
