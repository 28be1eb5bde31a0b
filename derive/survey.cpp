#include "derive/survey.h"

#include <algorithm>
#include <stdexcept>

#include "derive/helpers.h"

namespace shadesim {

std::vector<SceneInfo> load_scenes(const FrameSet& frames) {
  if (frames.size() == 0) throw std::invalid_argument("derive_config: no scenes given");
  std::vector<SceneInfo> scenes;
  for (size_t i = 0; i < frames.size(); ++i)
    scenes.push_back({frames.path(i), frames.at(i).scene()});
  return scenes;
}

LightColours light_colours(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg) {
  LightColours out;
  out.specular.assign(static_cast<size_t>(cfg.lights), 0.0);
  out.diffuse.assign(static_cast<size_t>(cfg.lights), 0.0);
  for (const auto& s : scenes) {
    for (size_t l = 0; l < s.scene.lights.size() && l < out.specular.size(); ++l) {
      const Vec3& light = s.scene.lights[l].colour;
      for (const auto& m : s.scene.materials) {
        for (int c = 0; c < 3; ++c) {
          out.specular[l] = std::max(out.specular[l], channel(m.specular, c) * channel(light, c));
          if (cfg.diffuse_multiply())
            out.diffuse[l] = std::max(out.diffuse[l], channel(m.diffuse, c) * channel(light, c));
        }
      }
    }
  }
  return out;
}

const DerivationRule kChannelsRule = {"channels", "1 if every scene is grey, else 3"};

std::string derive_channels(const std::vector<SceneInfo>& scenes, UnitConfig& cfg) {
  for (const auto& s : scenes) {
    if (!s.scene.is_grey()) {
      cfg.channels = 3;
      return s.path + " has colour: three channels";
    }
  }
  cfg.channels = 1;
  return "every scene is grey: one channel carries the image";
}

const DerivationRule kLightsRule = {"lights", "the most directional lights of any scene"};

std::string derive_lights(const std::vector<SceneInfo>& scenes, UnitConfig& cfg) {
  int lights = 0;
  std::string lights_scene;
  for (const auto& s : scenes) {
    if (static_cast<int>(s.scene.lights.size()) > lights) {
      lights = static_cast<int>(s.scene.lights.size());
      lights_scene = s.path;
    }
  }
  cfg.lights = lights;
  return "the most directional lights of any scene (" + lights_scene + ")";
}

const DerivationRule kDiffuseColourRule = {
    "diffuse_colour",
    "multiply with 3 channels (one N.L series per light, times kd_c L_c per pixel and channel), "
    "series with 1, where a multiply would remove no series (--diffuse-colour to choose)"};

std::string derive_diffuse_colour(const DeriveOptions& options, UnitConfig& cfg) {
  cfg.diffuse_colour = options.diffuse_colour.value_or(cfg.channels > 1 ? DiffuseColour::kMultiply
                                                                        : DiffuseColour::kSeries);
  if (options.diffuse_colour) return "as requested (--diffuse-colour)";
  if (cfg.channels > 1) {
    return "multiply: one N.L series per light (" + std::to_string(cfg.lights) +
           ") in place of one per light and channel (" + std::to_string(cfg.lights * cfg.channels) +
           "); each pixel multiplies max(0, N.L) by kd_c L_c from the MATERIAL";
  }
  return "series: one channel, so a multiply would remove no series";
}

}  // namespace shadesim
