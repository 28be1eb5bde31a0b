// libFuzzer target: the scene JSON reader (host/scene.h). Every input must load or throw
// SceneError with a message; anything else (crash, sanitizer report, other exception) fails.
#include <cstddef>
#include <cstdint>

#include "host/scene.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = shadesim::fuzz::write_input("scene.json", data, size);
  try {
    const shadesim::Scene scene = shadesim::load_scene(path);
    if (scene.materials.empty() || scene.objects.empty() || scene.lights.empty()) {
      shadesim::fuzz::fail("load_scene accepted a scene without materials, objects or lights");
    }
  } catch (const shadesim::SceneError& e) {
    shadesim::fuzz::require_message(e);
  }
  return 0;
}
