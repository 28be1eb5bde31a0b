// CycleEstimate: CycleModel's results for a whole stream with no input gaps and no
// back-pressure, computed in closed form per decoder item and per span instead of clock by clock.
// Exactly equal to run_cycle_model(words, Stimulus{}, unit) (sim/harness/cycle_run.h) in cycles,
// pixels, words, beats and every scanline's completion cycle (tests/cycle_estimate_test.cpp checks
// it), and on request its breakdown.
//
// The spec is CycleModel::clock(). With cmd_valid high until the last beat and pix_ready always
// high, the pix register always advances, so every stage is an elastic pipeline stage and each
// event time is a max of the times that enable it. For span k (in stream order; k-1 the span
// before it, whose terms are dropped for k = 0), with edges numbered as CycleModel counts cycles:
//
//   P_k   edge the decoder takes its SPAN header (pushed into the span queue, tri_queue > 1)
//   A_k   edge it enters setup stage s1:     no queue: A_k = P_k (the header goes straight in)
//                                            queue:    A_k = max(P_k + 1, S_{k-1}[1])
//   S_k[i] edge it enters stage i (s1 = 0, ..., engines = kSetupStages):
//           S_k[0] = A_k,  S_k[i] = max(S_k[i-1] + 1, S_{k-1}[i+1])   (stage i is free on the
//           edge its occupant moves on), and for the engines (L_k = S_k[kSetupStages])
//           L_k   = max(S_k[kSetupStages-1] + 1, E_{k-1})   (load_eng: s3 valid and the engines
//                                                            idle or emitting their last beat)
//   F_k   first emit: max(L_k + 1, E_{k-1} + interval)      (an iterative slot is busy for
//                                                            interval - 1 cycles after an emit)
//   E_k   last emit:  F_k + (beats(len_k, lanes) - 1) * interval
//   pixel j of the span leaves on cycle F_k + j * interval + latency + 1 (the slot's delay line
//   or the iterative unit's interval, then the pix register).
//
// The decoder is walked item by item (model/command_stream.h: one item per cycle, the next no
// earlier than the cycle after the last); a header that cannot go yet waits until its condition
// holds, and every condition only becomes true as time passes:
//   SPAN, no queue      s1 free: cycle >= S_{k-1}[1], and never in the item of a triangle tail
//   SPAN, queue         room in the queue: cycle >= A_{k-Q} + 1 (the span Q places earlier has
//                       left it); the run of SPAN headers in the beat goes as far as the room
//                       on that cycle, Q - (spans queued and not yet in s1)
//   TRIANGLE, queue     its bank's last queued span has entered s1: cycle >= A_last + 1
//   MATERIAL, TABLE     empty datapath: cycle >= E_last + latency + 1 (the last pixel has left
//                       the slot; the pix register does not count)
//   MATERIAL, two       the bank it switches to is free: cycle >= E_m + latency + 1 for the
//   material buffers    latest span m of that bank (spans carry the bank of the MATERIAL
//                       before them; MATERIALs alternate the banks)
// Host span setup (CycleConfig::host_setup): no setup stages. A SPAN's start values are taken
// like a TRIANGLE's coefficients (with the header, then the rest of the beat a cycle); D_k is
// the cycle its last words are taken (P_k when they all come with the header). Then
//   L_k = max(D_k + 1, E_{k-1})         (the start bank's entry is complete the cycle after)
//   F_k, E_k as above; and the header waits for a free entry of the start_depth-entry bank:
//   SPAN, host setup    cycle >= L_{k-start_depth} (that entry leaves for the engines then),
//                       and may go on its predecessor's last tail cycle.
// The run ends on the cycle after the later of the last beat's acceptance and the last pixel's
// leaving.
//
// The breakdown (run(words, true)): with no back-pressure a cycle is a pixel or a unit stall
// exactly when it lies in a span's busy interval (pipelined slot: [F_k + latency + 1,
// E_k + latency + 1], its pixels leaving; iterative: [F_k + 1, E_k + interval + 1], the unit
// holding a pixel or one leaving); every other cycle is a bubble charged, as CycleModel does, to
// the port's category span_latency() cycles earlier. The port's category is constant over each
// wait, item and payload run of the walk, so both are lists of intervals, counted against each
// other in one sweep.
//
// Per triangle it also reports what bounds it (TriangleCost).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "model/cycle_model.h"

namespace shadesim {

// One triangle's share of the decoder and of the engines, on the no-gap schedule.
struct TriangleCost {
  uint32_t index = 0;  // TRIANGLE commands before it in the stream
  int32_t xo = 0, yo = 0;
  uint32_t words = 0;  // header + coefficient words
  uint32_t spans = 0;  // SPAN headers between it and the next TRIANGLE
  uint64_t pixels = 0;
  // Cycles on which the decoder took words of this triangle (its header, coefficient words or
  // the SPAN headers after it), waiting cycles not counted: one item per cycle.
  uint64_t decoder_cycles = 0;
  // Cycles its pixels keep the engines busy: beats per span x the slot's interval.
  uint64_t engine_cycles = 0;
  // Setup-bound: the decoder needs more cycles for its words than the engines for its pixels,
  // so the engines idle unless a queue hides the difference; otherwise fill-bound.
  bool setup_bound() const { return decoder_cycles > engine_cycles; }
};

struct CycleEstimateRun {
  uint64_t cycles = 0;  // as CycleRun
  uint64_t pixels = 0;
  uint64_t words = 0;
  uint64_t beats = 0;
  std::vector<ScanlineDone> scanlines;
  std::vector<TriangleCost> triangles;      // in stream order
  std::optional<CycleBreakdown> breakdown;  // with run(words, true)
};

class CycleEstimate {
 public:
  // The two quantities pixel lanes change (with CycleModel::span_latency(), which the breakdown
  // takes from CycleModel): the setup stages between the span queue and the engines (s1..s3 in
  // rtl/shade_unit.sv), and the engine beats a span of `len` pixels takes: ceil(len / lanes).
  static constexpr int kSetupStages = 3;  // lane_fanout is combinational: no stage of its own
  static constexpr uint64_t beats(uint64_t len, uint64_t lanes) {
    return (len + lanes - 1) / lanes;
  }

  // Accepts exactly the units CycleModel accepts (its constructor is the check).
  explicit CycleEstimate(CycleConfig unit);

  // Throws std::invalid_argument for a stream the clocked model could never finish: a command
  // whose payload runs past the last word, or a SPAN of length 0 (both name the word index).
  // with_breakdown: also CycleModel's breakdown (exactly), from segments of the port's work and
  // the spans' busy intervals (costs memory per item; the figures alone need none).
  CycleEstimateRun run(const std::vector<uint64_t>& words, bool with_breakdown = false) const;

 private:
  CycleConfig unit_;
  int span_latency_;  // CycleModel::span_latency(): how far back a bubble's port category lies
};

}  // namespace shadesim
