// shadesim explore's engine (its options: sim/cli/explore.cpp): width sweeps of the bit-accurate
// model against error, cycles per pixel and area; the cheapest widths meeting an error budget; the
// Pareto front; the error of the chosen point split by source.
#include "explore/explore.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "derive/derive_config.h"
#include "model/command_stream.h"
#include "model/text_file.h"
#include "model/unit_config_file.h"
#include "sim/engines/area_report.h"
#include "sim/engines/derivation_cache.h"
#include "sim/engines/elapsed.h"
#include "sim/engines/explore.h"
#include "sim/engines/explore_csv.h"
#include "sim/engines/explore_front.h"
#include "sim/engines/explore_verify.h"
#include "sim/engines/fixed_text.h"
#include "sim/engines/unit_choice.h"

namespace shadesim {
namespace {

// ---------------------------------------------------------------- area

// The area every point shows: sim/engines/area_report.h's estimate_area(), which scales a
// Yosys-measured anchor of the same specular unit module by module. The anchors are the measured
// units in the area cache; when none has the start's specular unit, the start is synthesised once
// (minutes, cached for every later run).
AreaFunction area_model(const UnitConfig& start, const std::string& cache_dir) {
  std::vector<AreaReport> anchors = load_area_reports(cache_dir);
  // The sweep's span_setup knob needs a unit-setup anchor too: a host-setup unit has no span
  // setup to scale from (a unit-setup anchor serves both sites).
  std::vector<UnitConfig> needed = {start};
  if (start.host_setup()) {
    UnitConfig unit = start;
    unit.span_setup = SpanSetupSite::kUnit;
    unit.tri_queue = 2;  // config's default queue
    needed.push_back(unit);
  }
  for (const UnitConfig& u : needed) {
    const bool have_anchor = std::any_of(anchors.begin(), anchors.end(), [&](const AreaReport& r) {
      try {
        (void)estimate_area(u, {r});
        return true;
      } catch (const std::runtime_error&) {
        return false;
      }
    });
    if (have_anchor) continue;
    std::cerr << "explore: no measured " << to_string(u.specular.kind) << " unit with "
              << to_string(u.span_setup) << " span setup in " << cache_dir
              << " to scale areas from: synthesising it with Yosys once (minutes; cached)\n";
    AreaOptions ao;
    ao.cache_dir = cache_dir;
    ao.place_and_route = false;
    ao.breakdown = true;  // estimate_area scales the per-module cells
    ao.progress = &std::cerr;
    anchors.push_back(unit_area(u, ao));
  }
  auto shared = std::make_shared<const std::vector<AreaReport>>(std::move(anchors));
  return [shared](const UnitConfig& c) {
    const AreaEstimate e = estimate_area(c, *shared);
    return AreaFigure{static_cast<double>(e.cells), static_cast<double>(e.lut4),
                      "generic cells, " + e.label()};
  };
}

// ---------------------------------------------------------------- progress

// A progress bar with an ETA on stderr, only when stderr is a terminal.
class ProgressBar {
 public:
  ProgressBar() : tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(const std::string& phase, std::size_t done, std::size_t total) {
    if (!tty_) return;
    const auto now = std::chrono::steady_clock::now();
    if (phase != phase_) {
      phase_ = phase;
      phase_start_ = now;
    }
    // Redraw at most ten times a second: a point can take a millisecond.
    if (done != total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - phase_start_).count();
    const double eta =
        done ? elapsed / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
    constexpr int kWidth = 30;
    const int filled = total ? static_cast<int>(kWidth * done / total) : kWidth;
    std::cerr << "\r" << std::left << std::setw(14) << phase << " ["
              << std::string(static_cast<size_t>(filled), '#')
              << std::string(static_cast<size_t>(kWidth - filled), '.') << "] " << done << "/"
              << total << "  ETA " << std::fixed << std::setprecision(1) << eta << " s   "
              << std::flush;
    if (done == total) std::cerr << "\r" << std::string(80, ' ') << "\r" << std::flush;
  }

 private:
  bool tty_;
  std::string phase_;
  std::chrono::steady_clock::time_point phase_start_, last_draw_;
};

// ---------------------------------------------------------------- output

std::string per_channel_max(const ErrorStats& e, int channels) {
  std::string s;
  for (int c = 0; c < channels; ++c) {
    if (c) s += "/";
    s += std::to_string(e.max_code_lsb_channel[static_cast<size_t>(c)]);
  }
  return s;
}

std::string per_channel_mean(const ErrorStats& e, int channels) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(4);
  for (int c = 0; c < channels; ++c) {
    if (c) os << "/";
    os << e.mean_code_lsb_channel[static_cast<size_t>(c)];
  }
  return os.str();
}

double over_1lsb_pct(const ErrorStats& e) {
  return e.pixels ? 100.0 * static_cast<double>(e.pixels_over_1lsb) / static_cast<double>(e.pixels)
                  : 0.0;
}

nlohmann::json psnr_json(double db) {
  return std::isinf(db) ? nlohmann::json(nullptr) : nlohmann::json(db);
}

nlohmann::json point_json(const ExplorePoint& p, std::size_t index, int channels,
                          const ExploreJobOptions& o) {
  nlohmann::json j = {{"index", index}, {"phase", p.phase}, {"stage", p.stage},
                      {"knob", p.knob}, {"value", p.value}, {"valid", p.valid}};
  if (!p.valid) {
    j["invalid_reason"] = p.invalid_reason;
    return j;
  }
  const ErrorStats& e = p.figures.error;
  std::vector<int> max_ch;
  std::vector<double> mean_ch;
  for (int c = 0; c < channels; ++c) {
    max_ch.push_back(e.max_code_lsb_channel[static_cast<size_t>(c)]);
    mean_ch.push_back(e.mean_code_lsb_channel[static_cast<size_t>(c)]);
  }
  j["config"] = nlohmann::json::parse(config_to_json(p.config));
  j["config_text"] = p.config.to_string();
  j["error"] = {{"max_code_lsb", e.max_code_lsb},
                {"max_code_lsb_per_channel", max_ch},
                {"mean_code_lsb", e.mean_code_lsb},
                {"mean_code_lsb_per_channel", mean_ch},
                {"psnr_db", psnr_json(e.psnr_db)},
                {"max_real_lsb", e.max_real_lsb},
                {"pixels", e.pixels},
                {"pixels_over_1lsb", e.pixels_over_1lsb},
                {"pct_over_1lsb", over_1lsb_pct(e)}};
  j["cycles"] = p.figures.cycles;
  j["pixels"] = p.figures.pixels;
  j["cycles_per_pixel"] = p.figures.cycles_per_pixel;
  j["area"] = p.figures.area.cells;
  j["area_lut4"] = p.figures.area.lut4;
  j["area_metric"] = p.figures.area.metric;
  j["coefficients_out_of_range"] = p.figures.coefficients_out_of_range;
  j["meets_budget"] = p.meets_budget;
  j["pareto"] = p.pareto;
  if (p.measured) j["measured"] = measured_json(p, o);
  return j;
}

nlohmann::json part_json(const ErrorPart& p) {
  return {{"max_lsb", p.max_lsb}, {"mean_lsb", p.mean_lsb}};
}

nlohmann::json budget_json(const ErrorBudget& b) {
  return {{"scene", b.scene},
          {"function", part_json(b.function)},
          {"taylor", part_json(b.taylor)},
          {"quantization", part_json(b.quantization)},
          {"total", part_json(b.total)}};
}

void print_table(std::ostream& os, const std::vector<const ExplorePoint*>& rows, int channels,
                 const std::optional<std::size_t>& chosen, const std::vector<ExplorePoint>& all) {
  os << std::left << std::setw(12) << "phase" << std::setw(22) << "knob" << std::setw(8) << "value"
     << std::right << std::setw(10) << "max LSB" << std::setw(channels == 1 ? 9 : 23) << "mean LSB"
     << std::setw(9) << "PSNR dB" << std::setw(8) << ">1LSB%" << std::setw(8) << "cyc/px"
     << std::setw(9) << "area"
     << "   budget   (area: * Yosys-measured cells, else the estimate)\n";
  for (const ExplorePoint* p : rows) {
    const bool is_chosen = chosen && &all[*chosen] == p;
    os << std::left << std::setw(12) << p->phase << std::setw(22)
       << (p->knob.empty() ? "-" : p->knob) << std::setw(8) << (p->value.empty() ? "-" : p->value);
    if (!p->valid) {
      os << "invalid: " << p->invalid_reason << '\n';
      continue;
    }
    const ErrorStats& e = p->figures.error;
    std::ostringstream psnr;
    if (std::isinf(e.psnr_db))
      psnr << "inf";
    else
      psnr << std::fixed << std::setprecision(1) << e.psnr_db;
    os << std::right << std::setw(10) << per_channel_max(e, channels)
       << std::setw(channels == 1 ? 9 : 23) << per_channel_mean(e, channels) << std::setw(9)
       << psnr.str() << std::setw(8) << std::fixed << std::setprecision(2) << over_1lsb_pct(e)
       << std::setw(8) << std::setprecision(3) << p->figures.cycles_per_pixel << std::setw(9)
       << std::setprecision(0) << p->front_area() << (p->measured ? "*" : " ") << " "
       << (p->meets_budget ? "ok" : "over") << (p->pareto ? " pareto" : "")
       << (is_chosen ? " CHOSEN" : "") << '\n';
  }
}

void print_budget(std::ostream& os, const ErrorBudget& b, const std::string& what) {
  os << std::fixed << std::setprecision(3);
  os << "error by source, " << what << ", " << b.scene
     << " (output LSBs before rounding; max / mean)\n"
     << "  (1) shading function  " << std::setw(8) << b.function.max_lsb << " / "
     << std::setprecision(4) << b.function.mean_lsb << std::setprecision(3)
     << "   unit's function in double vs exact pow: change the unit or its fit, not a width\n"
     << "  (2) Taylor truncation " << std::setw(8) << b.taylor.max_lsb << " / "
     << std::setprecision(4) << b.taylor.mean_lsb << std::setprecision(3)
     << "   quadratics vs exact cosines: the setup budget (--setup-budget) subdivides, widths "
        "cannot\n"
     << "  (3) quantization      " << std::setw(8) << b.quantization.max_lsb << " / "
     << std::setprecision(4) << b.quantization.mean_lsb << std::setprecision(3)
     << "   bit-accurate model vs the same quadratics and function in double: the widths, incl.\n"
     << "                                             output rounding (<= 0.5 LSB unless out_bits "
        "grows)\n"
     << "  total                 " << std::setw(8) << b.total.max_lsb << " / "
     << std::setprecision(4) << b.total.mean_lsb << std::setprecision(3)
     << "   model vs reference; per pixel <= (1) + (2) + (3)\n";
}

// ---------------------------------------------------------------- the run

// What one explore run found: what it prints, writes as JSON and verifies in RTL.
struct ExploreRun {
  std::filesystem::path out_dir;
  UnitConfig start;
  std::string start_source;  // where the start came from, for the reader
  ExploreResult result;
  std::vector<ErrorBudget> chosen_budget, start_budget;  // one per scene
  std::vector<PointToVerify> config_files;        // written into out_dir: start, chosen, the front
  double host_s = 0, sweep_s = 0, measure_s = 0;  // wall-clock seconds of the phases

  int channels() const { return start.channels; }
  const std::string& area_metric() const {
    return result.points[result.start_index].figures.area.metric;
  }
  const ExplorePoint* chosen() const {
    return result.chosen ? &result.points[*result.chosen] : nullptr;
  }
};

std::filesystem::path explore_out_dir(const ExploreJobOptions& o) {
  if (!o.out_dir.empty()) return o.out_dir;
  return std::filesystem::path("out") / "explore" / std::filesystem::path(o.scenes.front()).stem();
}

// The start: a given config file, else the scenes' own smallest configuration.
void choose_start(const ExploreJobOptions& o, ExploreRun& run) {
  if (!o.config_path.empty() && o.config_path != kOwnUnit) {
    run.start = resolve_unit(o.config_path, o.scenes.front()).unit;
    run.start_source = o.config_path == kDefaultUnit ? "the default widths" : o.config_path;
  } else {
    DeriveOptions d;
    d.budget_lsb = o.budget_lsb > 0 ? std::optional<double>(o.budget_lsb) : std::nullopt;
    d.out_bits = o.out_bits;
    d.max_depth = o.max_depth;
    const CachedDerivation own = cached_derive_config(o.scenes, d, default_unit_cache_dir());
    run.start = own.derived.config;
    run.start_source = "the scenes' own configuration (shadesim config; " + own.origin() + ")";
  }
  if (!o.specular.empty()) {
    run.start.specular.kind = parse_specular_unit(o.specular, "--specular");
    run.start_source += ", specular unit " + o.specular + " (--specular)";
  }
  run.start.validate();
}

// The sweep from the start, then (unless --estimate-only) shadesim area on its front.
void sweep_and_measure(const ExploreJobOptions& o, ExploreScenes& scenes, ExploreRun& run) {
  ExploreOptions eo;
  eo.budget_lsb = o.budget_lsb;
  eo.jobs = o.jobs;
  eo.structure = !o.widths_only;
  ProgressBar bar;
  const AreaFunction area = area_model(run.start, o.area_cache);
  const MeasureFunction measure = o.estimate_only ? MeasureFunction() : front_measure(o);
  const auto sweep_start = std::chrono::steady_clock::now();
  run.result = explore(scenes, run.start, area, eo, std::ref(bar));
  run.sweep_s = seconds_since(sweep_start);
  const auto measure_start = std::chrono::steady_clock::now();
  if (!o.estimate_only) {
    measure_front(run.result, measure, [&](std::size_t i, std::size_t done, std::size_t total) {
      if (!o.quiet)
        std::cerr << "explore: shadesim area on Pareto point " << i << " (" << done + 1 << " of "
                  << total << " so far)\n";
    });
  }
  run.measure_s = seconds_since(measure_start);
}

void budget_errors(const ExploreScenes& scenes, std::size_t scene_count, ExploreRun& run) {
  for (std::size_t s = 0; s < scene_count; ++s) {
    run.start_budget.push_back(error_budget(scenes, s, run.start));
    if (run.chosen()) run.chosen_budget.push_back(error_budget(scenes, s, run.chosen()->config));
  }
}

// Config files of the start, the chosen point and the front, into --out, so any of them can be
// co-simulated or synthesised by file.
void write_point_configs(ExploreRun& run) {
  std::filesystem::create_directories(run.out_dir);
  const auto write_config = [&](const std::string& name, const UnitConfig& c) {
    const std::filesystem::path file = run.out_dir / (name + ".json");
    write_text_file(file, config_to_json(c) + '\n');
    run.config_files.push_back({name, c, file.string()});
  };
  write_config("start", run.start);
  if (run.chosen()) write_config("chosen", run.chosen()->config);
  for (std::size_t i = 0; i < run.result.points.size(); ++i) {
    if (run.result.points[i].pareto)
      write_config("pareto_" + std::to_string(i), run.result.points[i].config);
  }
}

// ---------------------------------------------------------------- the printed run
// One stream throughout: each part leaves its number format to the next, as they always have.

void print_start(std::ostream& os, const ExploreJobOptions& o, const ExploreRun& run) {
  os << "scenes       ";
  for (const auto& s : o.scenes) os << s << ' ';
  os << "\nstart        " << run.start.to_string() << "\n             from " << run.start_source
     << "\nbudget       max " << o.budget_lsb
     << " LSB (output codes vs the reference rounded by the same rule, every pixel and "
        "channel)\n"
     << "area         " << run.area_metric() << "\n\n";
}

// Every point, the search log, and the Pareto front (measured by Yosys unless --estimate-only).
void print_points(std::ostream& os, const ExploreJobOptions& o, const ExploreRun& run) {
  const ExploreResult& r = run.result;
  std::vector<const ExplorePoint*> rows;
  for (const auto& p : r.points) rows.push_back(&p);
  print_table(os, rows, run.channels(), r.chosen, r.points);
  os << "\nsearch\n";
  for (const auto& line : r.log) os << "  " << line << '\n';
  std::vector<const ExplorePoint*> front;
  for (const auto& p : r.points) {
    if (p.pareto) front.push_back(&p);
  }
  std::sort(front.begin(), front.end(), [](const ExplorePoint* a, const ExplorePoint* b) {
    return a->front_area() < b->front_area();
  });
  os << "\nPareto front (max LSB, mean LSB vs area and throughput: Mpixel/s where measured, "
        "else cycles/pixel\nbetween points of one pipelining), by area"
     << (o.estimate_only ? " - ESTIMATED areas (--estimate-only): not measured by Yosys"
                         : "; area: Yosys-measured cells")
     << "\n";
  print_table(os, front, run.channels(), r.chosen, r.points);
  os << '\n';
  if (!o.estimate_only) {
    print_measured_front(os, r, o);
    os << '\n';
  }
}

void print_chosen(std::ostream& os, const ExploreRun& run) {
  const ExplorePoint& c = *run.chosen();
  os << "chosen       " << c.config.to_string() << "\n             " << c.config.specular.describe()
     << ", spec_colour " << c.config.spec_colour.to_string() << "\n             max "
     << c.figures.error.max_code_lsb << " LSB, mean " << std::setprecision(4)
     << c.figures.error.mean_code_lsb << ", " << std::setprecision(3) << c.figures.cycles_per_pixel
     << " cycles/pixel, area " << std::setprecision(0) << c.figures.area.cells << " (start "
     << run.result.points[run.result.start_index].figures.area.cells << ")\n\n";
  for (const auto& b : run.chosen_budget) print_budget(os, b, "chosen point");
}

// No point meets the budget: which scenes no width can bring within it.
void print_no_choice(std::ostream& os, const ExploreJobOptions& o, const ExploreRun& run) {
  os << "chosen       none: no evaluated point meets max " << o.budget_lsb << " LSB\n";
  for (const auto& b : run.start_budget) {
    // Widths move only the quantization part; the rest is there at any width.
    const double fixed = b.function.max_lsb + b.taylor.max_lsb;
    if (fixed > o.budget_lsb) {
      os << "             " << b.scene << ": the shading function (" << std::setprecision(3)
         << b.function.max_lsb << " LSB) and the Taylor truncation (" << b.taylor.max_lsb
         << " LSB) are there at any width - no width can fix them; change the specular "
            "unit or\n"
         << "             its fit (function), or lower --setup-budget (Taylor)\n";
    }
  }
  os << '\n';
}

void print_files_and_time(std::ostream& os, const ExploreJobOptions& o, const ExploreRun& run) {
  const std::filesystem::path& out_dir = run.out_dir;
  os << "\nconfigs      " << (out_dir / "start.json").string()
     << (run.chosen() ? ", " + (out_dir / "chosen.json").string() : std::string())
     << ", pareto_<point>.json for the front (in " << out_dir.string() << ")\n"
     << "time         host setup " << std::setprecision(2) << run.host_s << " s, "
     << run.result.points.size() << " points in " << run.sweep_s << " s on " << o.jobs
     << " thread(s)"
     << (o.estimate_only ? std::string()
                         : ", shadesim area on the front " + fixed_text(run.measure_s, 1) + " s")
     << "\n";
  if (!o.json_path.empty()) os << "plot         scripts/plot " << o.json_path << "\n";
}

void print_run(std::ostream& os, const ExploreJobOptions& o, const ExploreRun& run) {
  print_start(os, o, run);
  print_points(os, o, run);
  if (run.chosen())
    print_chosen(os, run);
  else
    print_no_choice(os, o, run);
  for (const auto& b : run.start_budget) print_budget(os, b, "start point");
  print_files_and_time(os, o, run);
}

// --verify: the chosen point (or, when none meets the budget, the start) in RTL; --emit-jobs:
// the runs that would do it, written instead (then none is verified).
std::vector<Verification> verify_choice(const ExploreJobOptions& o, const ExploreRun& run) {
  std::vector<Verification> verified;
  if (!o.verify && o.emit_jobs.empty()) return verified;
  std::vector<PointToVerify> points;
  for (const auto& v : run.config_files) {
    if (v.name == (run.chosen() ? "chosen" : "start")) points.push_back(v);
  }
  if (!o.emit_jobs.empty()) {
    emit_verify_jobs(points, o.scenes, run.out_dir.string(), o.emit_jobs);
  } else {
    verified = verify_in_rtl(points, o.scenes, run.out_dir.string());
  }
  for (const auto& v : verified) {
    std::cout << "verified     " << v.name << ": "
              << (v.verified ? "yes - bit- and cycle-exact in RTL" : "NO") << " (" << v.passed
              << " runs passed, " << v.mismatched << " mismatched, " << v.errors << " error(s), "
              << v.skipped << " skipped; both backends, every scene; " << v.report << ")\n";
  }
  return verified;
}

nlohmann::json explore_json(const ExploreJobOptions& o, const ExploreRun& run,
                            const std::vector<Verification>& verified) {
  const ExploreResult& r = run.result;
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = 0; i < r.points.size(); ++i)
    points.push_back(point_json(r.points[i], i, run.channels(), o));
  nlohmann::json cb = nlohmann::json::array(), sb = nlohmann::json::array();
  for (const auto& b : run.chosen_budget) cb.push_back(budget_json(b));
  for (const auto& b : run.start_budget) sb.push_back(budget_json(b));
  nlohmann::json j = {
      {"kind", "explore"},
      {"scenes", o.scenes},
      {"budget_lsb", o.budget_lsb},
      {"area_metric", run.area_metric()},
      {"start", nlohmann::json::parse(config_to_json(run.start))},
      {"start_source", run.start_source},
      {"start_index", r.start_index},
      {"chosen_index", r.chosen ? nlohmann::json(*r.chosen) : nlohmann::json(nullptr)},
      {"points", points},
      {"search_log", r.log},
      {"error_budget", {{"chosen", cb}, {"start", sb}}},
      {"config_files", nlohmann::json::array()},
      {"seconds",
       {{"host_setup", run.host_s}, {"sweep", run.sweep_s}, {"measure_front", run.measure_s}}},
      {"front_measured", !o.estimate_only},
      {"jobs", o.jobs}};
  for (const auto& v : run.config_files)
    j["config_files"].push_back({{"name", v.name}, {"file", v.config_file}});
  const EstimateError ee = estimate_error(r);
  j["estimate_error"] = {
      {"points", ee.count}, {"median_pct", ee.median_pct}, {"max_pct", ee.max_pct}};
  j["verification"] = verification_json(verified);
  j["clock"] = clock_json(r, o);
  return j;
}

}  // namespace

int run_explore(const ExploreJobOptions& o) {
  ExploreRun run;
  run.out_dir = explore_out_dir(o);
  const auto t0 = std::chrono::steady_clock::now();
  choose_start(o, run);
  std::optional<double> setup_budget;
  if (!std::isnan(o.setup_budget_lsb)) setup_budget = o.setup_budget_lsb;
  ExploreScenes scenes(o.scenes, run.start, setup_budget, o.max_depth);
  run.host_s = seconds_since(t0);
  sweep_and_measure(o, scenes, run);
  budget_errors(scenes, o.scenes.size(), run);
  write_point_configs(run);

  if (!o.quiet) print_run(std::cout, o, run);
  const std::vector<Verification> verified = verify_choice(o, run);
  // Last, so a script's tail finds it; the exit status ignores it (reported, not enforced).
  if (!o.quiet && o.clock_mhz > 0)
    std::cout << "clock        " << clock_verdict(run.result, o).line << "\n";
  if (!o.json_path.empty())
    write_text_file(o.json_path, explore_json(o, run, verified).dump(2) + '\n');
  if (!o.csv_path.empty()) write_explore_csv(o.csv_path, run.result, run.channels(), o);
  const bool all_verified = std::all_of(verified.begin(), verified.end(),
                                        [](const Verification& v) { return v.verified; });
  return run.chosen() && all_verified ? 0 : 1;
}

}  // namespace shadesim
