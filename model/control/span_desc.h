// SpanDesc: a span as the unit's control carries it from the command decoder to the engines -
// shade_unit.sv's span_t {y, x0, len, last}. Valid bits and material banks are not part of it:
// the RTL keeps them beside the span (setup_ctrl's s*_v_q, material_bank's s*_mat_q), and so
// do the model classes.
#pragma once

#include "model/command_word.h"

namespace shadesim {

struct SpanDesc {
  int y = 0;
  int x0 = 0;
  int len = 0;        // 1..2^XY_BITS pixels
  bool last = false;  // last_in_row: its last pixel ends the scanline

  // The span of a SPAN header (span_queue.sv's beat_span, start_bank.sv's span_q).
  static constexpr SpanDesc of(CommandWord header) {
    return {header.span_y(), header.span_x0(), header.span_length(), header.span_last()};
  }
};

}  // namespace shadesim
