// CycleModel: the shading unit's control, clock by clock, in plain C++ — the timing of
// rtl/shade_unit.sv without its datapath. Usable on its own (fast cycle estimates: run()) or in
// lockstep with the RTL (clock()), where every scanline's completion cycle must match exactly.
//
// Mirrored structure (names as in the RTL): a command decoder (headers, payload counting;
// MATERIAL waits for an empty datapath), three span-setup stages s1..s3 with valid bits, the
// engines' run state (run, rem), and the pix output register with advance = !valid || ready.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/harness/stimulus.h"

namespace shadesim {

// Where a scanline ends: the cycle on which its end-of-row pixel leaves the unit.
struct ScanlineDone {
  int y = 0;
  uint64_t cycle = 0;
  int x = -1;  // x of the end-of-row pixel, when known
};

struct CycleRun {
  uint64_t cycles = 0;  // cycles until every word is accepted and every pixel has left
  uint64_t pixels = 0;
  uint64_t cmd_stall_cycles = 0;   // a word was offered but not accepted
  uint64_t backpressure_cycles = 0;  // a pixel was waiting and pix_ready was low
  std::vector<ScanlineDone> scanlines;
};

class CycleModel {
 public:
  // What happened on one clock edge.
  struct Edge {
    bool cmd_ready = false;  // combinational, before the edge
    bool cmd_fire = false;
    bool pix_fire = false;   // a pixel left on this edge
    bool pix_eor = false;
    int pix_x = 0, pix_y = 0;
  };

  // Inputs as seen just before the edge; advances the state by one clock.
  Edge clock(bool cmd_valid, uint64_t cmd_word, bool pix_ready);

  // Nothing in flight and no pixel waiting.
  bool idle() const { return !in_payload_ && !s_[0].valid && !s_[1].valid && !s_[2].valid && !run_ && !pix_valid_; }

  // Runs a whole stream with the stimulus's gaps and back-pressure.
  static CycleRun run(const std::vector<uint64_t>& words, const Stimulus& stim);

 private:
  struct Span {
    bool valid = false;
    int y = 0, x0 = 0, len = 0;
    bool last = false;
  };
  enum class Payload { kSkip, kMaterial, kTriangle, kTable };

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
  // Output register
  bool pix_valid_ = false;
  int pix_x_ = 0, pix_y_ = 0;
  bool pix_eor_ = false;
};

}  // namespace shadesim
