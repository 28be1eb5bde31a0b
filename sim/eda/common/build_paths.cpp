#include "sim/eda/common/build_paths.h"

namespace shadesim {

std::string source_dir() { return SHADESIM_SOURCE_DIR; }
std::string binary_dir() { return SHADESIM_BINARY_DIR; }

}  // namespace shadesim
