// libFuzzer target: the mesh loader (host/mesh.h, through assimp). An input is
// "<extension>\n<file bytes>": assimp picks its importer by the extension first, so the
// extension is part of what is fuzzed. Every input must give a mesh whose triangles index its
// vertices and whose normals are unit length, or throw SceneError with a message.
// This is the product's path, a forked import per input, so it runs a few hundred inputs a
// second. The import cannot run in process instead: Debian's assimp crashes, leaks and asks for
// absurd allocations on fuzzed files (a trial in libFuzzer's fork mode: 26 crashes and
// leak reports in assimp in 1,309 inputs), which the product's import child survives.
#include <pthread.h>
#include <sanitizer/common_interface_defs.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <string>

#include "host/mesh.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  size_t newline = 0;
  while (newline < size && newline <= 8 && data[newline] != '\n') ++newline;
  if (newline == 0 || newline > 8 || newline == size) return 0;
  std::string extension(reinterpret_cast<const char*>(data), newline);
  for (char c : extension) {
    if (!std::isalnum(static_cast<unsigned char>(c))) return 0;
  }
  const std::string path =
      shadesim::fuzz::write_input("mesh." + extension, data + newline + 1, size - newline - 1);
  try {
    shadesim::fuzz::check_mesh(shadesim::load_mesh_file(path));
  } catch (const shadesim::SceneError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}

// load_mesh_file imports in a forked child. Debian's assimp is not instrumented, but the child
// inherits libFuzzer's death callback: when ASan ends the child (operator new cannot return null
// under ASan, so assimp's absurd allocations from corrupt element counts abort it instead of
// throwing std::bad_alloc), the callback would save the input as a crash although the parent
// reports it as a clean SceneError. Only the parent's fate counts, so the child drops it.
namespace {
[[maybe_unused]] const bool child_drops_death_callback = [] {
  pthread_atfork(nullptr, nullptr, [] { __sanitizer_set_death_callback(nullptr); });
  return true;
}();
}  // namespace
