// A scene's switching activity on a unit: the scene encoded for exactly that unit, co-simulated
// on its traced C++ build (built into the RTL cache when missing), and the FST it writes read
// by sim/eda/power/activity.h. The engine runs the co-simulation; power/ only reads traces.
#pragma once

#include <string>

#include "model/unit_config.h"
#include "sim/eda/power/activity.h"

namespace shadesim {

struct ActivityOptions {
  std::string work_dir;   // required: the stream, unit, trace and log files go here
  std::string cache_dir;  // the RTL build cache; empty: <build>/rtl-cache
  int make_jobs = 1;      // compiler processes of the traced build, if it must be built
  std::string top = "shade_unit";
};

// The scene's stream on `unit` (prepare_frame on exactly that unit), co-simulated on its traced
// C++ build (built into the cache when missing) with no gaps or back-pressure; the run must pass.
// Throws std::runtime_error (with the co-simulation's output) when it does not, and
// std::invalid_argument when the scene does not fit the unit.
SceneActivity scene_activity(const UnitConfig& unit, const std::string& scene_path,
                             const ActivityOptions& options);

}  // namespace shadesim
