// A scene's switching activity from an FST trace (sim/eda/power/activity.h).
#include "sim/eda/power/activity.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "sim/harness/cosim.h"

namespace shadesim {

SceneActivity activity_from_trace(const std::string& fst_path, const std::string& top,
                                  uint64_t pixels, const std::string& clock) {
  FstActivity f = read_fst_activity(fst_path, top, kWaveUnitsPerCycle / 2);
  SceneActivity a;
  a.signals = std::move(f.toggles);
  a.duty = std::move(f.duty);
  a.pixels = pixels;
  const auto clk = a.signals.find(clock);
  if (clk == a.signals.end() || clk->second == 0)
    throw std::runtime_error("activity: " + fst_path + " has no toggles of " + clock);
  a.cycles =
      (clk->second + 1) / 2;  // low in the first sample, then up and down, the last fall unseen
  return a;
}

std::string activity_to_json(const SceneActivity& a) {
  nlohmann::json j;
  j["scene"] = a.scene;
  j["unit"] = a.unit;
  j["cycles"] = a.cycles;
  j["run_cycles"] = a.run_cycles;
  j["pixels"] = a.pixels;
  j["signals"] = a.signals;
  j["duty"] = a.duty;
  j["idle_noise_toggles"] = a.idle_noise_toggles;
  j["notes"] = a.notes;
  return j.dump(1);
}

SceneActivity activity_from_json(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  SceneActivity a;
  a.scene = j.at("scene").get<std::string>();
  a.unit = j.at("unit").get<std::string>();
  a.cycles = j.at("cycles").get<uint64_t>();
  a.run_cycles = j.at("run_cycles").get<uint64_t>();
  a.pixels = j.at("pixels").get<uint64_t>();
  a.signals = j.at("signals").get<ToggleMap>();
  a.duty = j.at("duty").get<DutyMap>();
  a.idle_noise_toggles = j.at("idle_noise_toggles").get<uint64_t>();
  a.notes = j.at("notes").get<std::vector<std::string>>();
  return a;
}

}  // namespace shadesim
