// What identifies this shadesim's code, for caches of results the code computes (the derived
// own unit, sim/engines/derivation_cache.h): the content hash of the running executable.
//
// Why the executable and not `shadesim --version`: the version's commit is the checkout's at
// configure time (CMake does not re-run it), so an edit rebuilt since, committed or not, would
// keep the old identity and a cache would return what the old code derived. The executable's
// bytes change with any change to the code linked into it; the build is reproducible (no time
// stamps), so a rebuild of the same sources keeps its entries. A change anywhere in the binary
// misses too: the price of never reusing a stale result.
#pragma once

#include <string>

namespace shadesim {

// 32 hex digits (ContentHash of /proc/self/exe). Reads the file on every call (a few MB, about
// a millisecond): callers call it once per derivation. Throws std::runtime_error when the
// executable cannot be read (no /proc).
std::string executable_digest();

}  // namespace shadesim
