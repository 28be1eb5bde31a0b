// libFuzzer target: the scene JSON reader (host/scene.h), on the file's text in memory
// (parse_scene: what load_scene runs after reading the file). Every input must load or throw
// SceneError with a message; anything else (crash, sanitizer report, other exception) fails.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "host/scene.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

// scenes/hard/long_span.json names its mesh relative to the scene file: put that mesh beside
// the fuzzed scene, so mutations of it reach the mesh loader too.
const bool mesh_beside_scene = [] {
  std::ifstream in(SHADESIM_SOURCE_DIR "/scenes/hard/long_span_tri.obj", std::ios::binary);
  std::ofstream out(shadesim::fuzz::private_dir() + "/long_span_tri.obj", std::ios::binary);
  out << in.rdbuf();
  return static_cast<bool>(out);
}();

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (!mesh_beside_scene) shadesim::fuzz::fail("cannot copy long_span_tri.obj beside the scene");
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const shadesim::Scene scene =
        shadesim::parse_scene(text, shadesim::fuzz::private_dir() + "/scene.json");
    if (scene.materials.empty() || scene.objects.empty() || scene.lights.empty()) {
      shadesim::fuzz::fail("load_scene accepted a scene without materials, objects or lights");
    }
  } catch (const shadesim::SceneError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}
