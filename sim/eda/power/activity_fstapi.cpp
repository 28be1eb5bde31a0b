// The FST reader and writer Verilator ships (gtkwave's fstapi.c, with fastlz and lz4), compiled
// as Verilator's own verilated_fst_c.cpp compiles them, for sim/eda/power/activity_fst.cpp.
// CMakeLists.txt keeps this file out of the unity build, without warnings (not our code), and
// defines SHADESIM_HAVE_FSTAPI when Verilator's include folder and zlib are there.
#ifdef SHADESIM_HAVE_FSTAPI
#define FST_CONFIG_INCLUDE "fst_config.h"
// NOLINTBEGIN(bugprone-suspicious-include): the C sources are this file's content, as above
#include "gtkwave/fastlz.c"
#include "gtkwave/fstapi.c"
#include "gtkwave/lz4.c"
// NOLINTEND(bugprone-suspicious-include)
#endif
