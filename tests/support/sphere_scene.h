// The small scene several derivation tests vary: a 96x96 sphere of `tessellation` under one
// light of `light_colour` with one material, a finite eye.
#pragma once

#include <nlohmann/json.hpp>

namespace shadesim::test {

inline nlohmann::json sphere_scene(const nlohmann::json& light_colour,
                                   const nlohmann::json& material, int tessellation) {
  return {{"image", {{"width", 96}, {"height", 96}}},
          {"camera",
           {{"type", "perspective"},
            {"position", {0, 0, 5}},
            {"target", {0, 0, 0}},
            {"up", {0, 1, 0}},
            {"fov_y", 40}}},
          {"lights", {{{"direction", {0.5, 0.6, 1}}, {"colour", light_colour}}}},
          {"ambient_light", 1.0},
          {"eye", "finite"},
          {"materials", {material}},
          {"objects",
           {{{"name", "ball"},
             {"type", "sphere"},
             {"material", material["name"]},
             {"radius", 1.0},
             {"tessellation", tessellation}}}}};
}

}  // namespace shadesim::test
