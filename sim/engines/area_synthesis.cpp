// unit_area (sim/engines/area_report.h): one shadesim area run. Looks the unit up in the cache,
// runs the flows that are missing side by side (generic, iCE40, and the liberty flow when asked
// for), then nextpnr where the unit fits an HX8K, and writes the cache entries.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <iomanip>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "model/text_file.h"
#include "sim/eda/common/build_paths.h"
#include "sim/eda/common/content_hash.h"
#include "sim/eda/common/flow_tools.h"
#include "sim/eda/yosys/area_generic.h"
#include "sim/engines/area_report.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using flow_tools::write_atomically;

// A run's tools and inputs: the figures depend on these and on the scripts only.
struct AreaInputs {
  FlowInputs flow;
  std::string nextpnr;  // empty without place and route
};

AreaInputs area_inputs(const std::vector<VerilogParameter>& parameters, const AreaOptions& o) {
  AreaInputs in;
  in.flow.chparam = yosys_chparam_args(parameters);
  in.flow.yosys = flow_tools::find_tool(o.yosys, "yosys");
  in.nextpnr = o.place_and_route ? flow_tools::find_tool(o.nextpnr, "nextpnr-ice40") : "";
  in.flow.files = flow_tools::rtl_sources(o.rtl_dir.empty() ? source_dir() + "/rtl" : o.rtl_dir);
  in.flow.yosys_version = flow_tools::tool_version(in.flow.yosys, {"-V"});
  return in;
}

// Cache key: everything the figures depend on. The file names are in the script text.
std::string area_key(const FlowInputs& in, bool breakdown, bool pnr,
                     const std::string& nextpnr_version) {
  ContentHash h;
  h.add("shadesim-area-v3");
  h.add(in.chparam);
  for (const auto& f : in.files) {
    h.add(f.filename().string());
    h.add(read_text_file(f.string()));
  }
  h.add(in.yosys_version);
  h.add(generic_flow::flat_script());
  h.add(ice40_flow::synth_script());
  h.add(generic_flow::memory_script());
  if (breakdown) h.add(generic_flow::breakdown_script());
  if (pnr) {
    h.add(nextpnr_version);
    ice40_flow::add_place_and_route_recipe(h);
  }
  return h.hex();
}

// The cache entries that answer the request `key` stands for: its own, then any that ran more
// (breakdown, place and route), which also answer a request for less.
std::vector<fs::path> cache_candidates(const AreaInputs& in, const std::string& key,
                                       const std::string& nextpnr_version, const AreaOptions& o) {
  std::vector<fs::path> candidates = {fs::path(o.cache_dir) / (key + ".json")};
  std::string np_version = nextpnr_version;
  if (!o.place_and_route) {
    try {
      np_version = flow_tools::tool_version(flow_tools::find_tool(o.nextpnr, "nextpnr-ice40"),
                                            {"--version"});
    } catch (const MissingToolError&) {
      // no nextpnr: only entries without place and route can be wanted
    }
  }
  for (const bool b : {o.breakdown, true}) {
    for (const bool pnr : {o.place_and_route, true}) {
      if (pnr && np_version.empty()) continue;
      candidates.push_back(fs::path(o.cache_dir) /
                           (area_key(in.flow, b, pnr, np_version) + ".json"));
    }
  }
  return candidates;
}

std::optional<AreaReport> cached_area(const AreaInputs& in, const AreaReport& r,
                                      const AreaOptions& o) {
  for (const auto& c : cache_candidates(in, r.key, r.nextpnr_version, o)) {
    if (!fs::exists(c)) continue;
    AreaReport cached = area_report_from_json(read_text_file(c.string()), c.string());
    cached.from_cache = true;
    generic_flow::check_series(cached);
    if (o.progress) *o.progress << "[area] cache hit " << c.string() << "\n";
    return cached;
  }
  return std::nullopt;
}

struct SynthesisJob {
  std::string label;
  std::future<void> done;
  bool finished = false;
};

// Waits for every job, with one progress line for all of them: which are still running and for
// how long. Rethrows the first failure.
void wait_for_syntheses(std::vector<SynthesisJob>& jobs, const AreaOptions& o,
                        std::chrono::steady_clock::time_point t0) {
  const bool terminal = o.progress == &std::cerr && ::isatty(STDERR_FILENO);
  for (int ticks = 0;; ++ticks) {
    std::string running;
    for (auto& j : jobs) {
      if (!j.finished && j.done.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
        j.finished = true;
      if (!j.finished) running += (running.empty() ? "" : ", ") + j.label;
    }
    if (running.empty()) break;
    if (o.progress && ticks > 0 && (terminal || ticks % 30 == 0)) {
      const auto el =
          std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - t0);
      *o.progress << (terminal ? "\r" : "") << "[area] running: " << running << " ... "
                  << el.count() << " s" << (terminal ? "   " : "\n") << std::flush;
    }
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  std::exception_ptr error;
  for (auto& j : jobs) {
    try {
      j.done.get();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (o.progress) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *o.progress << (terminal ? "\r" : "") << "[area] " << (error ? "failed" : "done") << " after "
                << std::fixed << std::setprecision(1) << el << " s"
                << (terminal ? "                                        " : "") << "\n";
  }
  if (error) std::rethrow_exception(error);
}

// One Yosys flow into `work` as a job: its script NAME.ys, log NAME.log.
SynthesisJob yosys_job(const FlowInputs& in, const fs::path& work, const std::string& name,
                       const std::string& flow, const std::string& label) {
  return {label, std::async(std::launch::async, [&in, work, name, flow, label] {
            const fs::path script = work / (name + ".ys");
            write_atomically(script, flow_tools::yosys_script(in.files, in.chparam, flow, work));
            flow_tools::run_tool(
                {in.yosys, "-q", "-l", (work / (name + ".log")).string(), script.string()},
                work / (name + ".out"), "yosys " + label, nullptr);
          })};
}

// The generic flow's syntheses (flat, table memories, with o.breakdown per-module) and
// synth_ice40, into `work`, side by side.
std::vector<SynthesisJob> synthesis_jobs(const FlowInputs& in, const fs::path& work,
                                         const AreaOptions& o) {
  std::vector<SynthesisJob> jobs;
  jobs.push_back(yosys_job(in, work, "flat", generic_flow::flat_script(), "flat synthesis"));
  jobs.push_back(yosys_job(in, work, "ice40", ice40_flow::synth_script(), "synth_ice40"));
  jobs.push_back(yosys_job(in, work, "memory", generic_flow::memory_script(), "table memories"));
  if (o.breakdown) {
    jobs.push_back(
        yosys_job(in, work, "breakdown", generic_flow::breakdown_script(), "per-module synthesis"));
  }
  return jobs;
}

// The generic and iCE40 figures of a fresh run into r (whose parameters, versions and key are
// set), once its syntheses are done; returns whether the work folder must be kept (a failed
// placement's logs).
bool read_generic_and_ice40(const AreaInputs& in, const fs::path& work, const AreaOptions& o,
                            AreaReport& r) {
  generic_flow::read_syntheses(work, o.breakdown, r);
  ice40_flow::read_synthesis(work, r.ice40);
  if (!o.place_and_route) {
    r.ice40.pnr_note = "place and route not run (--no-pnr)";
  } else if (!r.ice40.fits_hx8k) {
    r.ice40.pnr_note = "no Fmax: the design does not fit an HX8K";
  } else {
    return ice40_flow::place_and_route(in.flow, in.nextpnr, r.parameters, work, o.progress,
                                       r.ice40);
  }
  return false;
}

// The liberty flow's job, into work/liberty; its report lands in `out`.
SynthesisJob liberty_job(const LibertyRun& run, const fs::path& work, const AreaOptions& o,
                         LibertyReport& out) {
  fs::create_directories(work / "liberty");
  return {"liberty mapping and OpenSTA", std::async(std::launch::async, [&run, work, &o, &out] {
            out = run_liberty_flow(run, work / "liberty", o.cache_dir);
          })};
}

}  // namespace

AreaReport unit_area(const UnitConfig& unit, const AreaOptions& o) {
  AreaReport r;
  r.parameters = shade_unit_parameters(unit);  // validates `unit`
  const AreaInputs in = area_inputs(r.parameters, o);
  r.yosys_version = in.flow.yosys_version;
  if (o.place_and_route) r.nextpnr_version = flow_tools::tool_version(in.nextpnr, {"--version"});
  r.key = area_key(in.flow, o.breakdown, o.place_and_route, r.nextpnr_version);
  std::optional<LibertyRun> lib_run;
  if (o.liberty) lib_run = prepare_liberty_run(in.flow, *o.liberty);

  // Each part from the cache where it can be.
  std::optional<AreaReport> cached;
  std::optional<LibertyReport> lib_cached;
  if (!o.cache_dir.empty()) {
    fs::create_directories(o.cache_dir);
    cached = cached_area(in, r, o);
    if (lib_run) lib_cached = cached_liberty(*lib_run, o.cache_dir);
    if (lib_cached && o.progress)
      *o.progress << "[area] cache hit " << lib_cached->netlist_path << " (liberty)\n";
  }
  if (cached && (!lib_run || lib_cached)) {
    cached->liberty = lib_cached;
    return *cached;
  }

  const fs::path work = flow_tools::make_work_folder(o.cache_dir, r.key);
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu_before = flow_tools::children_cpu_seconds();
  std::vector<SynthesisJob> jobs;
  if (!cached) jobs = synthesis_jobs(in.flow, work, o);
  LibertyReport lib_report;
  if (lib_run && !lib_cached) jobs.push_back(liberty_job(*lib_run, work, o, lib_report));
  wait_for_syntheses(jobs, o, t0);
  bool keep_work = false;
  if (cached) {
    r = *cached;
  } else {
    keep_work = read_generic_and_ice40(in, work, o, r);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cpu_seconds = flow_tools::children_cpu_seconds() - cpu_before;
    if (!o.cache_dir.empty())
      write_atomically(fs::path(o.cache_dir) / (r.key + ".json"), area_report_to_json(r));
  }
  if (lib_run) r.liberty = lib_cached ? *lib_cached : lib_report;
  if (!keep_work) {
    std::error_code ec;
    fs::remove_all(work, ec);
  }
  return r;
}

}  // namespace shadesim
