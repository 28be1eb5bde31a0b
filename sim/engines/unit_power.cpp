#include "sim/engines/unit_power.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

#include "model/command_stream.h"
#include "model/text_file.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/engines/scene_activity.h"

namespace shadesim {
namespace fs = std::filesystem;
namespace {

// The version of this step's own recipe: bump it when the activity run changes, so old entries
// are not taken for new ones (the OpenSTA scripts' commands are hashed themselves).
constexpr const char* kPowerRecipe =
    "area power v1: scene_activity (traced cpp build, no gaps) + "
    "netlist_power (default activity 0.1, duty 0.5)";

std::string power_key(const UnitConfig& unit, const std::string& scene,
                      const LibertyReport& liberty) {
  ContentHash h;
  h.add(kPowerRecipe)
      .add(power_scripts_commands())
      .add(liberty.key)
      .add(config_to_json(unit))
      .add(read_text_file(scene));
  std::ostringstream mhz;
  mhz << std::setprecision(17) << liberty.fmax_mhz;
  return h.add(mhz.str()).hex();
}

PowerReport measure(const UnitConfig& unit, const std::string& scene, const LibertyReport& l,
                    const fs::path& work, const std::string& cache_dir, std::ostream* progress) {
  if (progress) *progress << "[area] power: the scene's co-simulation, traced ...\n" << std::flush;
  ActivityOptions ao;
  ao.work_dir = (work / "activity").string();
  fs::create_directories(ao.work_dir);
  const SceneActivity activity = scene_activity(unit, scene, ao);
  PowerOptions po;
  const std::string log = liberty_log_path(cache_dir, l.key);
  if (fs::exists(log)) po.excluded_registers = fsm_recoded_registers(read_text_file(log));
  if (progress) *progress << "[area] power: OpenSTA report_power ...\n" << std::flush;
  return netlist_power(l.netlist_path, l.liberty_path, "shade_unit", activity, l.fmax_mhz,
                       (work / "power").string(), po);
}

}  // namespace

AreaPower scene_power(const UnitConfig& unit, const std::string& scene,
                      const LibertyReport& liberty, const std::string& cache_dir,
                      std::ostream* progress) {
  AreaPower p;
  p.key = power_key(unit, scene, liberty);
  const fs::path entry = fs::path(cache_dir) / ("power-" + p.key + ".json");
  if (!cache_dir.empty() && fs::exists(entry)) {
    const nlohmann::json j = nlohmann::json::parse(read_text_file(entry.string()));
    p.report = power_report_from_json(j.at("report").dump());
    p.seconds = j.value("seconds", 0.0);
    p.from_cache = true;
    return p;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path root = cache_dir.empty() ? fs::temp_directory_path() : fs::path(cache_dir);
  std::string tmpl = (root / ("work-power-" + p.key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(tmpl + ": cannot create a work folder");
  const fs::path work = tmpl;
  p.report = measure(unit, scene, liberty, work, cache_dir, progress);
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!cache_dir.empty()) {
    nlohmann::json j;
    j["report"] = nlohmann::json::parse(power_report_to_json(p.report));
    j["seconds"] = p.seconds;
    j["scene"] = scene;
    flow_tools::write_atomically(entry, j.dump(2) + "\n");
  }
  std::error_code ec;
  fs::remove_all(work, ec);  // kept only when a step threw (its logs say why)
  return p;
}

void print_area_power(std::ostream& os, const AreaPower& p) {
  const PowerReport& r = p.report;
  os << std::fixed << std::setprecision(1) << "  energy       " << r.pj_per_pixel << " pJ/pixel, "
     << r.scene.total_mw << " mW at Fmax " << r.clock_mhz << " MHz (internal "
     << r.scene.internal_mw << ", switching " << r.scene.switching_mw << ", leakage "
     << std::setprecision(4) << r.scene.leakage_mw << std::setprecision(1) << " mW)\n"
     << "               from the scene's own activity: " << r.coverage_text() << ";\n"
     << "               " << r.cycles << " cycles, " << r.pixels
     << " pixels, no gaps or back-pressure; combinational nets by OpenSTA's propagation\n"
     << "               (zero delay: no glitches; no wires, no clock tree; docs/power.md)\n"
     << "  default      " << r.default_pj_per_pixel << " pJ/pixel, " << r.default_activity.total_mw
     << " mW with every net at OpenSTA's global activity " << std::setprecision(2)
     << r.default_activity_value << std::setprecision(1) << " (the usual guess, for comparison)\n"
     << "  clock only   " << r.clock_only.total_mw
     << " mW with every data pin still (the clock pins and leakage)\n"
     << "  power time   " << p.seconds << " s"
     << (p.from_cache ? " when measured (this run: a cache hit)" : "") << "\n";
}

}  // namespace shadesim
