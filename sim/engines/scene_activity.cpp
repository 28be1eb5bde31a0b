// A scene's switching activity from its traced co-simulation (sim/engines/scene_activity.h).
#include "sim/engines/scene_activity.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "host/frame.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/verilator/rtl_build.h"
#include "sim/harness/cosim.h"

namespace shadesim {
// A named namespace, not an anonymous one: sim/ is compiled as unity files (CMakeLists.txt).
namespace scene_activity_impl {

namespace fs = std::filesystem;

// The traced C++ build of `unit` (built into the cache when missing).
std::string traced_executable(const UnitConfig& unit, const ActivityOptions& o, uint64_t pixels) {
  RtlConfig build;
  build.name = "power";
  build.unit = unit;
  RtlBuildOptions bo;
  bo.cache_dir = o.cache_dir;
  bo.make_jobs = o.make_jobs;
  bo.quiet = true;
  bo.optimization = choose_optimization(4 * pixels);  // regress's estimate: 4 cycles/px
  return ensure_rtl_build(build, CosimBackend::kCppTrace, bo).executable;
}

// Runs the co-simulation and its traced re-run; returns its --json result.
nlohmann::json run_traced(const std::string& exe, const fs::path& dir) {
  const fs::path json = dir / "result.json", log = dir / "cosim.log";
  fs::remove(dir / "trace.fst");
  const ProcessResult r = run_process({exe,
                                       "--unit",
                                       (dir / "unit.json").string(),
                                       "--config",
                                       "power",
                                       "--stream",
                                       (dir / "stream.cmds").string(),
                                       "--seed",
                                       "1",
                                       "--gap-pct",
                                       "0",
                                       "--max-gap",
                                       "1",
                                       "--stall-pct",
                                       "0",
                                       "--save-dir",
                                       (dir / "failing").string(),
                                       "--trace-run",
                                       (dir / "trace.fst").string(),
                                       "--json",
                                       json.string()},
                                      log.string());
  if (r.exit_code != 0) {
    throw std::runtime_error("activity: the co-simulation of the scene failed (exit " +
                             std::to_string(r.exit_code) + "); the power of a unit that does " +
                             "not match its model means nothing. " + log.string() + ":\n" +
                             read_text_file(log.string()));
  }
  return nlohmann::json::parse(read_text_file(json.string()));
}

}  // namespace scene_activity_impl

SceneActivity scene_activity(const UnitConfig& unit, const std::string& scene_path,
                             const ActivityOptions& o) {
  namespace fs = std::filesystem;
  if (o.work_dir.empty()) throw std::invalid_argument("scene_activity: no work folder");
  const fs::path dir(o.work_dir);
  fs::create_directories(dir);
  FrameOptions fo;
  fo.base = unit;
  fo.fixed_unit = true;
  const PreparedFrame f = prepare_frame(scene_path, fo);
  const CommandStream& stream = f.encoded.stream;
  stream.save((dir / "stream.cmds").string());
  write_text_file((dir / "unit.json").string(), config_to_json(stream.config) + "\n");

  const std::string exe =
      scene_activity_impl::traced_executable(stream.config, o, f.encoded.stats.pixels);
  const nlohmann::json result = scene_activity_impl::run_traced(exe, dir);
  SceneActivity a =
      activity_from_trace((dir / "trace.fst").string(), o.top, result.at("pixels").get<uint64_t>());
  a.scene = scene_path;
  a.unit = stream.config.to_string();
  a.run_cycles = result.at("cycles").get<uint64_t>();
  const PortStimulus ps = port_stimulus(stream.config, stream);
  if (a.cycles != ps.run_cycles) {
    throw std::runtime_error("activity: clk_i rose " + std::to_string(a.cycles) +
                             " times in the trace, but the harness clocks " +
                             std::to_string(ps.run_cycles) + " cycles");
  }
  a.idle_noise_toggles = ps.idle_noise;
  a.notes = {
      "toggles and duty: the traced C++ build's FST of every cycle (--trace-run), the scene's "
      "stream with no gaps or back-pressure",
      "cycles: " + std::to_string(a.run_cycles) + " frame cycles + " +
          std::to_string(a.cycles - a.run_cycles) + " drain cycles (reset not traced)",
      std::to_string(a.idle_noise_toggles) +
          " cmd_data_i toggles are the harness's idle noise after the last beat"};
  return a;
}

}  // namespace shadesim
