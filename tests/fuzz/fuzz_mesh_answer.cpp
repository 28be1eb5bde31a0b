// libFuzzer target: the caller's half of a mesh import (mesh_from_import_answer in
// host/mesh_import.h), the code of ours that reads what assimp made of a file. An input is an
// import process's answer as sent over the socket: 'M', a part count and each part's positions,
// normals and triangle indices (element counts, then raw floats and uint32s), or 'E' and an
// error message. Every answer a fuzzed file could draw from assimp is one of these byte strings,
// so this target reaches the decoder's and the mesh checks' cases (NaN and huge coordinates,
// indices out of range, zero normals, truncated or trailing bytes) without assimp's cost per
// file, which bounds fuzz_mesh at a few hundred inputs a second. Its seeds are real answers for
// assimp-testmodels' files (mesh_answer_seeds.cpp). Every input must give a mesh whose
// triangles index its vertices and whose normals are unit length, or throw SceneError with a
// message.
#include <cstddef>
#include <cstdint>
#include <string>

#include "host/mesh_import.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string answer(reinterpret_cast<const char*>(data), size);
  try {
    shadesim::fuzz::check_mesh(shadesim::mesh_from_import_answer("fuzzed.obj", answer));
  } catch (const shadesim::SceneError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}
