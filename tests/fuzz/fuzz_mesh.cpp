// libFuzzer target: the mesh loader (host/mesh_import.h, through assimp). An input is
// "<extension>\n<file bytes>": assimp picks its importer by the extension first, so the
// extension is part of what is fuzzed. Every input must give a mesh whose triangles index its
// vertices and whose normals are unit length, or throw SceneError with a message.
// This is the product's path: the import runs in a separate process, which the product's
// MeshImporter keeps across files, so one fork serves up to kImportsPerProcess inputs. The
// import cannot run in this process instead: Debian's assimp crashes, leaks and asks for absurd
// allocations on fuzzed files (a trial in libFuzzer's fork mode: 26 crashes and leak reports in
// assimp in 1,309 inputs), which the import process survives or dies of alone.
#include <pthread.h>
#include <sanitizer/common_interface_defs.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <string>

#include "host/mesh_import.h"
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
    // One importer for the whole run; libFuzzer's entry point leaves nowhere else to keep it.
    // Its CPU limit per file is well inside -timeout (scripts/fuzz, cmake/fuzz.cmake), so a
    // runaway import is seen ending in the product's SceneError, not as the fuzzer's timeout.
    static shadesim::MeshImporter importer(10);
    shadesim::fuzz::check_mesh(importer.load(path));
  } catch (const shadesim::SceneError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}

// The import process is a fork of this one. Debian's assimp is not instrumented, but the child
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
