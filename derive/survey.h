// The scene survey: what the scenes are before any width is derived (their paths and scenes, the
// colour words their materials and lights make) and the fields that follow from that alone:
// channels, lights and the diffuse colour's site.
#pragma once

#include <string>
#include <vector>

#include "derive/derive_config.h"
#include "host/prepared_scene.h"
#include "host/scene.h"
#include "model/unit_config.h"

namespace shadesim {

struct SceneInfo {
  std::string path;
  const Scene& scene;  // the prepared frame's (FrameSet)
};

// The frames' scenes, in order. Throws std::invalid_argument for none.
std::vector<SceneInfo> load_scenes(const FrameSet& frames);

// What the colour words carry, per light: the largest specular colour ks_c L_c and, with the
// diffuse colour multiplied, the largest kd_c L_c, over every scene, material and channel.
struct LightColours {
  std::vector<double> specular, diffuse;  // indexed by light
  double max() const {
    double m = 0;
    for (double v : specular) m = std::max(m, v);
    for (double v : diffuse) m = std::max(m, v);
    return m;
  }
};

LightColours light_colours(const std::vector<SceneInfo>& scenes, const UnitConfig& cfg);

// Each sets its field of cfg and returns why (its reason).
std::string derive_channels(const std::vector<SceneInfo>& scenes, UnitConfig& cfg);
std::string derive_lights(const std::vector<SceneInfo>& scenes, UnitConfig& cfg);
// One N.L series per light in place of one per light and channel, where that removes series.
std::string derive_diffuse_colour(const DeriveOptions& options, UnitConfig& cfg);

extern const DerivationRule kChannelsRule, kLightsRule, kDiffuseColourRule;

}  // namespace shadesim
