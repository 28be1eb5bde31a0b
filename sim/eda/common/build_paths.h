// Where this build's checkout and build directory are: the on-demand RTL builds read the
// checkout's rtl/ and sim/harness/ and link this build's libraries; the caches live in the build
// directory. One file (sim/eda/common/build_paths.cpp) holds the two paths, compiled on its own, so
// that every other object of sim/ is the same in any checkout (ccache shares them between
// worktrees).
#pragma once

#include <string>

namespace shadesim {

// The checkout shadesim was built from.
std::string source_dir();
// The build directory shadesim was built in.
std::string binary_dir();

}  // namespace shadesim
