#include "sim/eda/common/build_identity.h"

#include <fstream>
#include <stdexcept>
#include <vector>

#include "sim/eda/common/content_hash.h"

namespace shadesim {

std::string executable_digest() {
  // The running image itself, not the path shell.h's self_executable() names: a rebuild may
  // have replaced the file at that path since this process started.
  const char* self = "/proc/self/exe";
  std::ifstream in(self, std::ios::binary);
  if (!in) throw std::runtime_error(std::string(self) + ": cannot read this executable");
  // Streamed in fixed 1 MiB blocks, one ContentHash field each: the digest depends on the bytes
  // alone, and the file is never held whole.
  ContentHash h;
  h.add("shadesim executable");
  std::vector<char> block(1 << 20);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const std::streamsize n = in.gcount();
    if (n > 0) h.add(std::string_view(block.data(), static_cast<size_t>(n)));
  }
  if (in.bad()) throw std::runtime_error(std::string(self) + ": read failed");
  return h.hex();
}

}  // namespace shadesim
