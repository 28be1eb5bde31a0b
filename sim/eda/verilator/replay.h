// The one home of replay lines' start: "shadesim cosim --backend B" and every option
// that chose which executable ran (--cache, --netlist, --netlist-cache), so a printed replay line
// runs when pasted. shadesim cosim and regress pass it to the co-simulation (--replay-prefix),
// whose replay_line (sim/harness/cosim_run.cpp) adds the build, fault, stream and stimulus;
// regress's own replay lines (a timeout, a crash) start with it too.
#pragma once

#include <string>

#include "sim/eda/common/shell.h"

namespace shadesim {

// "shadesim cosim --backend cpp --cache DIR --netlist --netlist-cache DIR": empty folders are
// the defaults and left out.
inline std::string cosim_replay_prefix(const std::string& backend, const std::string& cache,
                                       bool netlist, const std::string& netlist_cache) {
  std::string s = "shadesim cosim --backend " + shell_word(backend);
  if (!cache.empty()) s += " --cache " + shell_word(cache);
  if (netlist) s += " --netlist";
  if (netlist && !netlist_cache.empty()) s += " --netlist-cache " + shell_word(netlist_cache);
  return s;
}

}  // namespace shadesim
