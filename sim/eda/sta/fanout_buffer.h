// Fanout buffering of a mapped netlist, a small repair_design: every net that drives more than
// `max_fanout` cell input pins gets a tree of the library's strongest buffer
// (sim/eda/sta/liberty.h strongest_buffer), so no net drives more than max_fanout of them.
//
// Why it is needed: ABC's `buffer -p` buffers what ABC maps, but not the outputs of the
// flip-flops dfflibmap placed outside ABC, and not the input ports: on the specular unit one
// DFFSR output drove 228 pins, a 7 ns path at osu018's typical corner with no wire load.
//
// The rule: the sinks (cell input pins, in the netlist's order) are split into
// ceil(sinks / max_fanout) groups of near-equal size, each behind one buffer; the buffers are
// split again the same way until the driver drives at most max_fanout of them. Output ports stay
// on the original net (they are not counted: a port's load is the surrounding design's). Nets
// that reach a clock pin (`clock : true`) are left alone: the analysis clock is ideal, and a
// clock tree is not this flow's business. Constants (Yosys's "0"/"1" bits) have no net.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "sim/eda/sta/liberty.h"

namespace shadesim {

struct FanoutBufferResult {
  std::string buffer_cell;         // the library cell used
  int max_fanout = 0;              // the rule's limit
  int64_t nets_buffered = 0;       // nets that got a tree
  int64_t buffers = 0;             // buffer cells added
  int64_t largest_fanout = 0;      // the most cell input pins one net drove before
  int64_t clock_nets_skipped = 0;  // nets over the limit left alone because they clock flip-flops
};

// Buffers module `top` of a Yosys `write_json` document in place. Pin directions come from the
// library's cells, else from a module of the document (a blackbox such as the table RAM), else
// from the cell's port_directions; a cell type with none of them is an error naming it (and
// `source`, the document's file). New cells are named fanout_buf_N, their output nets
// fanout_buf_N_y. Throws std::invalid_argument for max_fanout < 2.
FanoutBufferResult buffer_fanout(nlohmann::json& netlist, const std::string& top,
                                 const LibertyLibrary& lib, int max_fanout,
                                 const std::string& source);

}  // namespace shadesim
