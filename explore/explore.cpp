#include "explore/explore.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "derive/pipelining.h"
#include "host/encode.h"
#include "host/specular_setup.h"
#include "model/command_stream.h"
#include "model/cycle_estimate.h"
#include "model/cycle_model.h"
#include "model/shade_unit.h"

namespace shadesim {

// ---------------------------------------------------------------- scenes and host setup

ExploreScenes::ExploreScenes(std::vector<std::string> paths, const UnitConfig& start,
                             std::optional<double> setup_budget_lsb, int max_depth)
    : paths_(std::move(paths)),
      start_(start),
      setup_budget_lsb_(setup_budget_lsb),
      max_depth_(max_depth) {
  if (paths_.empty()) throw std::invalid_argument("explore: no scene given");
  prepare(start.out_bits);
}

void ExploreScenes::prepare(int out_bits) {
  if (by_out_bits_.count(out_bits)) return;
  std::vector<std::shared_ptr<const HostSetup>> setups;
  for (const auto& path : paths_) {
    FrameOptions fo;
    fo.base = start_;
    fo.base.out_bits = out_bits;
    fo.budget_lsb = setup_budget_lsb_;
    fo.max_depth = max_depth_;
    fo.fixed_unit = true;  // one structure for every scene and point
    auto h = std::make_shared<HostSetup>();
    h->frame = prepare_frame(path, fo);
    h->reference = render_reference(h->frame.setup.triangles, h->frame.visibility, h->frame.scene,
                                    h->frame.config.channels);
    setups.push_back(std::move(h));
  }
  by_out_bits_.emplace(out_bits, std::move(setups));
}

const HostSetup& ExploreScenes::setup(std::size_t scene, int out_bits) const {
  const auto it = by_out_bits_.find(out_bits);
  if (it == by_out_bits_.end() || scene >= it->second.size()) {
    throw std::logic_error("explore: host setup for out_bits " + std::to_string(out_bits) +
                           " not prepared");
  }
  return *it->second[scene];
}

// ---------------------------------------------------------------- one point

PointFigures evaluate_point(const ExploreScenes& scenes, const UnitConfig& config,
                            const AreaFunction& area) {
  PointFigures p;
  double sum_abs = 0, sum_sq = 0;
  std::array<double, kMaxChannels> sum_abs_channel{};
  const double peak = std::ldexp(1.0, config.out_bits) - 1.0;
  std::vector<PixelOut> pixels;
  for (std::size_t s = 0; s < scenes.paths().size(); ++s) {
    const HostSetup& h = scenes.setup(s, config.out_bits);
    const PreparedFrame& f = h.frame;
    const EncodedFrame enc = encode_frame(f.scene, config, f.setup, f.visibility);
    p.coefficients_out_of_range += enc.stats.coefficients_out_of_range;
    ShadeUnit unit(config);
    pixels.clear();
    pixels.reserve(enc.stats.pixels);
    for (const auto& cmd : enc.stream.commands) {
      unit.consume(cmd, [&pixels](const PixelOut& px) { pixels.push_back(px); });
    }
    const ErrorStats e =
        compare_to_reference(pixels, h.reference.values, f.visibility.owner, f.scene.width,
                             f.scene.height, config.channels, config.out_bits)
            .stats;
    // The unit's whole timing: its slot, port width, triangle queue and pixel lanes.
    // (CycleEstimate: exactly the clocked CycleModel's figures with no gaps or back-pressure.)
    const CycleEstimateRun run = CycleEstimate(CycleConfig::of(config)).run(enc.stream.encode());
    p.cycles += run.cycles;
    p.pixels += run.pixels;

    ErrorStats& t = p.error;
    t.pixels += e.pixels;
    t.max_code_lsb = std::max(t.max_code_lsb, e.max_code_lsb);
    t.max_real_lsb = std::max(t.max_real_lsb, e.max_real_lsb);
    t.pixels_over_1lsb += e.pixels_over_1lsb;
    const double n = static_cast<double>(e.pixels);
    sum_abs += e.mean_code_lsb * n * config.channels;
    if (!std::isinf(e.psnr_db))
      sum_sq += peak * peak / std::pow(10.0, e.psnr_db / 10.0) * n * config.channels;
    for (int c = 0; c < config.channels; ++c) {
      const auto k = static_cast<std::size_t>(c);
      t.max_code_lsb_channel[k] = std::max(t.max_code_lsb_channel[k], e.max_code_lsb_channel[k]);
      sum_abs_channel[k] += e.mean_code_lsb_channel[k] * n;
    }
  }
  ErrorStats& t = p.error;
  if (t.pixels > 0) {
    const double samples = static_cast<double>(t.pixels) * config.channels;
    t.mean_code_lsb = sum_abs / samples;
    const double mse = sum_sq / samples;
    t.psnr_db =
        mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
    for (int c = 0; c < config.channels; ++c) {
      t.mean_code_lsb_channel[static_cast<std::size_t>(c)] =
          sum_abs_channel[static_cast<std::size_t>(c)] / static_cast<double>(t.pixels);
    }
  }
  p.cycles_per_pixel =
      p.pixels ? static_cast<double>(p.cycles) / static_cast<double>(p.pixels) : 0.0;
  if (area) p.area = area(config);
  return p;
}

// ---------------------------------------------------------------- the search

namespace {

// Evaluates the points of one batch in `jobs` threads; duplicates of earlier configurations
// (by their JSON) reuse those figures.
class Evaluator {
 public:
  Evaluator(ExploreScenes& scenes, const AreaFunction& area, const ExploreOptions& options,
            const ExploreProgress& progress, std::vector<ExplorePoint>& points)
      : scenes_(scenes), area_(area), options_(options), progress_(progress), points_(points) {}

  // Appends new points for the configurations not seen before; returns each one's index.
  std::vector<std::size_t> run(const std::string& phase, std::vector<ExplorePoint> batch) {
    std::vector<std::size_t> index(batch.size());
    std::vector<std::size_t> todo;  // into points_
    for (std::size_t i = 0; i < batch.size(); ++i) {
      ExplorePoint& p = batch[i];
      try {
        p.config.validate();
      } catch (const std::invalid_argument& e) {
        p.valid = false;
        p.invalid_reason = e.what();
      }
      const std::string key = config_to_json(p.config);
      const auto seen = by_key_.find(key);
      if (seen != by_key_.end()) {
        index[i] = seen->second;
        continue;
      }
      if (p.valid) scenes_.prepare(p.config.out_bits);
      p.phase = phase;
      points_.push_back(std::move(p));
      index[i] = points_.size() - 1;
      by_key_.emplace(key, index[i]);
      if (points_.back().valid) todo.push_back(index[i]);
    }
    std::atomic<std::size_t> next{0}, done{0};
    std::mutex progress_mutex;
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto worker = [&]() {
      for (std::size_t k; (k = next.fetch_add(1)) < todo.size();) {
        ExplorePoint& p = points_[todo[k]];
        try {
          p.figures = evaluate_point(scenes_, p.config, area_);
          p.meets_budget = p.figures.error.max_code_lsb <= options_.budget_lsb;
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = todo.size();
        }
        const std::size_t d = ++done;
        if (progress_) {
          const std::lock_guard<std::mutex> lock(progress_mutex);
          progress_(phase, d, todo.size());
        }
      }
    };
    const int threads = std::max(1, std::min<int>(options_.jobs, static_cast<int>(todo.size())));
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    return index;
  }

 private:
  ExploreScenes& scenes_;
  const AreaFunction& area_;
  const ExploreOptions& options_;
  const ExploreProgress& progress_;
  std::vector<ExplorePoint>& points_;
  std::map<std::string, std::size_t> by_key_;
};

// The cheaper of two points; on equal area the earlier (narrower) one.
bool cheaper(const ExplorePoint& a, const ExplorePoint& b) {
  return a.figures.area.cells < b.figures.area.cells;
}

std::string knob_setting(const Knob& k, const UnitConfig& c) {
  const int v = k.read(c);
  for (std::size_t i = 0; i < k.values.size(); ++i) {
    if (k.values[i] == v) return k.labels[i];
  }
  return std::to_string(v);
}

std::string describe(const ExplorePoint& p) {
  std::string s = "max " + std::to_string(p.figures.error.max_code_lsb) + " LSB";
  char buf[96];
  std::snprintf(buf, sizeof buf, " (real %.3f), mean %.4f, area %.0f", p.figures.error.max_real_lsb,
                p.figures.error.mean_code_lsb, p.figures.area.cells);
  return s + buf;
}

}  // namespace

namespace {

// How a's throughput compares with b's (mark_pareto): +1 better, 0 the same, -1 worse; none when
// they cannot be ordered. Mpixel/s where both have a measured Fmax on one site, else cycles per
// pixel between units of one pipelining: a pipeline register costs a cycle of latency and buys
// clock, so until both are measured a point of another pipelining is neither faster nor slower.
std::optional<int> throughput_order(const ExplorePoint& a, const ExplorePoint& b) {
  const auto order = [](double x, double y) { return x > y ? 1 : x < y ? -1 : 0; };
  const auto la = a.library_mpixel_per_s(), lb = b.library_mpixel_per_s();
  if (la && lb) return order(*la, *lb);
  const auto ia = a.mpixel_per_s(), ib = b.mpixel_per_s();
  if (ia && ib) return order(*ia, *ib);
  const Pipelining pa = pipelining_of(a.config), pb = pipelining_of(b.config);
  if (pa.combine_stages != pb.combine_stages || pa.square_stages != pb.square_stages)
    return std::nullopt;
  return order(b.figures.cycles_per_pixel, a.figures.cycles_per_pixel);
}

// Whether q dominates p: no worse in error, area and throughput, and better in one.
bool dominates(const ExplorePoint& q, const ExplorePoint& p) {
  const std::optional<int> t = throughput_order(q, p);
  if (!t || *t < 0) return false;
  const ErrorStats &eq = q.figures.error, &ep = p.figures.error;
  const bool no_worse = eq.max_code_lsb <= ep.max_code_lsb &&
                        eq.mean_code_lsb <= ep.mean_code_lsb && q.front_area() <= p.front_area();
  const bool better = eq.max_code_lsb < ep.max_code_lsb || eq.mean_code_lsb < ep.mean_code_lsb ||
                      q.front_area() < p.front_area() || *t > 0;
  return no_worse && better;
}

}  // namespace

void mark_pareto(std::vector<ExplorePoint>& points, int out_bits) {
  auto takes_part = [out_bits](const ExplorePoint& p) {
    return p.valid && p.config.out_bits == out_bits;
  };
  for (auto& p : points) {
    p.pareto = takes_part(p);
    if (!p.pareto) continue;
    for (const auto& q : points) {
      if (&q != &p && takes_part(q) && dominates(q, p)) {
        p.pareto = false;
        break;
      }
    }
  }
}

std::optional<double> ExplorePoint::mpixel_per_s() const {
  if (!measured || !measured->fmax_mhz || !(figures.cycles_per_pixel > 0)) return std::nullopt;
  return *measured->fmax_mhz / figures.cycles_per_pixel;
}

std::optional<double> ExplorePoint::library_mpixel_per_s() const {
  if (!measured || !measured->library_fmax_mhz || !(figures.cycles_per_pixel > 0))
    return std::nullopt;
  return *measured->library_fmax_mhz / figures.cycles_per_pixel;
}

std::size_t measure_front(ExploreResult& result, const MeasureFunction& measure,
                          const MeasureProgress& progress) {
  const int out_bits = result.start.out_bits;
  std::size_t measured = 0;
  for (;;) {
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < result.points.size(); ++i) {
      const ExplorePoint& p = result.points[i];
      const bool wanted = p.pareto || (result.chosen && *result.chosen == i);
      if (wanted && p.valid && !p.measured) todo.push_back(i);
    }
    if (todo.empty()) return measured;
    for (std::size_t k = 0; k < todo.size(); ++k) {
      if (progress) progress(todo[k], measured + k, measured + todo.size());
      result.points[todo[k]].measured = measure(result.points[todo[k]].config);
    }
    measured += todo.size();
    mark_pareto(result.points, out_bits);
  }
}

EstimateError estimate_error(const ExploreResult& result) {
  std::vector<double> pct;
  for (const auto& p : result.points) {
    if (!p.measured || !(p.measured->cells > 0)) continue;
    pct.push_back(100.0 * std::abs(p.figures.area.cells / p.measured->cells - 1.0));
  }
  EstimateError e;
  e.count = pct.size();
  if (pct.empty()) return e;
  std::sort(pct.begin(), pct.end());
  const std::size_t n = pct.size();
  e.median_pct = n % 2 ? pct[n / 2] : 0.5 * (pct[n / 2 - 1] + pct[n / 2]);
  e.max_pct = pct.back();
  return e;
}

namespace {

void check_options(const ExploreOptions& options) {
  if (!(options.budget_lsb >= 0) || !std::isfinite(options.budget_lsb)) {
    throw std::invalid_argument("explore: budget " + std::to_string(options.budget_lsb) +
                                " LSB, expected a finite value >= 0");
  }
  if (options.jobs < 1) throw std::invalid_argument("explore: jobs must be >= 1");
}

// The start point, evaluated and logged; an invalid start is an error.
std::size_t evaluate_start(Evaluator& eval, ExploreResult& r, const UnitConfig& start) {
  ExplorePoint sp;
  sp.config = start;
  const std::size_t index = eval.run("start", {sp}).front();
  const ExplorePoint start_point = r.points[index];
  if (!start_point.valid)
    throw std::invalid_argument("explore: start " + start_point.invalid_reason);
  r.log.push_back("start " + start.to_string() + ": " + describe(start_point) +
                  (start_point.meets_budget ? "" : " - breaks the budget"));
  return index;
}

// The per-stage sweep's points (indices into the result's points) and the knob each sweeps.
struct StageSweep {
  std::vector<std::size_t> points;
  std::vector<std::size_t> knob;
};

// 1. Every knob's values alone, the other knobs at the start configuration.
StageSweep sweep_each_knob(Evaluator& eval, const std::vector<Knob>& knobs,
                           const UnitConfig& start) {
  std::vector<ExplorePoint> batch;
  StageSweep sweep;
  for (std::size_t k = 0; k < knobs.size(); ++k) {
    for (std::size_t v = 0; v < knobs[k].values.size(); ++v) {
      ExplorePoint p;
      p.config = start;
      knobs[k].apply(p.config, knobs[k].values[v]);
      p.stage = knobs[k].stage;
      p.knob = knobs[k].name;
      p.value = knobs[k].labels[v];
      batch.push_back(std::move(p));
      sweep.knob.push_back(k);
    }
  }
  sweep.points = eval.run("per-stage", std::move(batch));
  return sweep;
}

// Knob k's cheapest swept value that meets the budget alone, if any.
std::optional<std::size_t> cheapest_meeting_budget(const std::vector<ExplorePoint>& points,
                                                   const StageSweep& sweep, std::size_t k) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    if (sweep.knob[i] != k) continue;
    const ExplorePoint& p = points[sweep.points[i]];
    if (!p.valid || !p.meets_budget) continue;
    if (!best || cheaper(p, points[*best])) best = sweep.points[i];
  }
  return best;
}

// The start with each searched knob at its per-stage minimum (else its start value), logged.
UnitConfig combine_minima(ExploreResult& r, const std::vector<Knob>& knobs, const UnitConfig& start,
                          const StageSweep& sweep) {
  UnitConfig joint = start;
  for (std::size_t k = 0; k < knobs.size(); ++k) {
    if (!knobs[k].searched) continue;
    const std::optional<std::size_t> best = cheapest_meeting_budget(r.points, sweep, k);
    if (best) {
      knobs[k].apply(joint, knobs[k].read(r.points[*best].config));
      r.log.push_back("stage " + knobs[k].stage + ": " + knobs[k].name + " = " +
                      knob_setting(knobs[k], joint) + " (start " + knob_setting(knobs[k], start) +
                      "), " + describe(r.points[*best]));
    } else {
      r.log.push_back("stage " + knobs[k].stage + ": " + knobs[k].name +
                      " - no value meets the budget alone; kept " + knob_setting(knobs[k], start));
    }
  }
  return joint;
}

// Each searched knob one step wider than in `cur` (numeric knobs the next value, choices back to
// the start's), as candidate points.
std::vector<ExplorePoint> wider_steps(const std::vector<Knob>& knobs, const UnitConfig& cur,
                                      const UnitConfig& start) {
  std::vector<ExplorePoint> candidates;
  for (const Knob& k : knobs) {
    if (!k.searched) continue;
    const int v = k.read(cur);
    const auto it = std::find(k.values.begin(), k.values.end(), v);
    std::optional<int> wider;
    if (k.choice) {
      if (v != k.read(start)) wider = k.read(start);
    } else if (it != k.values.end() && it + 1 != k.values.end()) {
      wider = *(it + 1);
    }
    if (!wider) continue;
    ExplorePoint c;
    c.config = cur;
    k.apply(c.config, *wider);
    c.stage = k.stage;
    c.knob = k.name;
    c.value = knob_setting(k, c.config);
    candidates.push_back(std::move(c));
  }
  return candidates;
}

// The step to take among the points tried from `current`: the cheapest that meets the budget,
// else the most error reduction per area added, else (all invalid) the first, so widening still
// ends. `why` says which.
std::size_t pick_step(const std::vector<ExplorePoint>& points,
                      const std::vector<std::size_t>& tried, std::size_t current,
                      std::string& why) {
  std::optional<std::size_t> pick;
  for (std::size_t i : tried) {
    const ExplorePoint& p = points[i];
    if (p.valid && p.meets_budget && (!pick || cheaper(p, points[*pick]))) pick = i;
  }
  why = "meets the budget, cheapest such step";
  if (pick) return *pick;
  const bool cur_valid = points[current].valid;
  const double cur_err = cur_valid ? points[current].figures.error.max_real_lsb +
                                         points[current].figures.error.mean_code_lsb
                                   : std::numeric_limits<double>::infinity();
  const double cur_area = cur_valid ? points[current].figures.area.cells : 0.0;
  double best_score = -std::numeric_limits<double>::infinity();
  for (std::size_t i : tried) {
    const ExplorePoint& p = points[i];
    if (!p.valid) continue;
    const double gain = cur_err - (p.figures.error.max_real_lsb + p.figures.error.mean_code_lsb);
    const double cost = std::max(p.figures.area.cells - cur_area, 1e-9);
    const double score = std::isinf(gain) ? -p.figures.area.cells : gain / cost;
    if (!pick || score > best_score) best_score = score, pick = i;
  }
  why = "most error reduction per area added";
  return pick ? *pick : tried.front();
}

// 2. Joint refinement: the per-stage minima combined, then one knob a step wider at a time until
// the budget is met or no step is left. Returns the last point.
std::size_t refine_jointly(Evaluator& eval, ExploreResult& r, const std::vector<Knob>& knobs,
                           const UnitConfig& start, const UnitConfig& joint) {
  ExplorePoint jp;
  jp.config = joint;
  std::size_t current = eval.run("joint", {jp}).front();
  if (!r.points[current].valid) {
    // The minima are valid alone but not together (e.g. coef.int below series.int): start from
    // the start's integer bits, which every knob combination accepts.
    r.log.push_back("joint: per-stage minima combined are invalid (" +
                    r.points[current].invalid_reason + "); widening from there");
  } else {
    r.log.push_back("joint: per-stage minima combined " + joint.to_string() + ": " +
                    describe(r.points[current]));
  }
  for (int step = 1; !(r.points[current].valid && r.points[current].meets_budget); ++step) {
    std::vector<ExplorePoint> candidates = wider_steps(knobs, r.points[current].config, start);
    if (candidates.empty()) {
      r.log.push_back(
          "joint: every knob is at its widest swept value and the budget is still broken");
      break;
    }
    const std::vector<std::size_t> tried =
        eval.run("joint step " + std::to_string(step), std::move(candidates));
    std::string why;
    const std::size_t pick = pick_step(r.points, tried, current, why);
    if (pick == current) {
      r.log.push_back("joint: no step changes the configuration; stopping");
      break;
    }
    current = pick;
    r.log.push_back(
        "joint step " + std::to_string(step) + ": " + r.points[current].knob + " -> " +
        r.points[current].value + " (" + why + "): " +
        (r.points[current].valid ? describe(r.points[current]) : r.points[current].invalid_reason));
  }
  return current;
}

}  // namespace

ExploreResult explore(ExploreScenes& scenes, const UnitConfig& start, const AreaFunction& area,
                      const ExploreOptions& options, const ExploreProgress& progress) {
  check_options(options);
  ExploreResult r;
  r.start = start;
  Evaluator eval(scenes, area, options, progress, r.points);
  r.start_index = evaluate_start(eval, r, start);
  const std::vector<Knob> knobs = knobs_for(start, options.structure);
  const UnitConfig joint = combine_minima(r, knobs, start, sweep_each_knob(eval, knobs, start));
  const std::size_t last = refine_jointly(eval, r, knobs, start, joint);
  if (r.points[last].valid && r.points[last].meets_budget) r.chosen = last;
  mark_pareto(r.points, start.out_bits);
  return r;
}

// ---------------------------------------------------------------- error by source

namespace {

// The value an image shows in output LSBs, with the top code standing for full scale (as
// compare_to_reference measures real error).
double shown(double r, double scale) { return std::min(r * scale, scale - 1.0); }

ErrorPart image_difference(const ReferenceImage& a, const ReferenceImage& b,
                           const std::vector<int32_t>& owner, int out_bits) {
  ErrorPart e;
  const double scale = std::ldexp(1.0, out_bits);
  double sum = 0;
  std::size_t samples = 0;
  for (std::size_t i = 0; i < owner.size(); ++i) {
    if (owner[i] < 0) continue;
    for (int c = 0; c < a.channels; ++c) {
      const std::size_t k = i * static_cast<std::size_t>(a.channels) + static_cast<std::size_t>(c);
      const double d = std::fabs(shown(a.values[k], scale) - shown(b.values[k], scale));
      e.max_lsb = std::max(e.max_lsb, d);
      sum += d;
      ++samples;
    }
  }
  e.mean_lsb = samples ? sum / static_cast<double>(samples) : 0.0;
  return e;
}

ErrorPart model_difference(const std::vector<PixelOut>& pixels, const ReferenceImage& img,
                           int out_bits) {
  ErrorPart e;
  const double scale = std::ldexp(1.0, out_bits);
  double sum = 0;
  std::size_t samples = 0;
  for (const PixelOut& p : pixels) {
    const std::size_t pixel =
        static_cast<std::size_t>(p.y) * static_cast<std::size_t>(img.width) + p.x;
    for (int c = 0; c < img.channels; ++c) {
      const double r =
          img.values[pixel * static_cast<std::size_t>(img.channels) + static_cast<std::size_t>(c)];
      const double d = std::fabs(p.colour[static_cast<std::size_t>(c)] - shown(r, scale));
      e.max_lsb = std::max(e.max_lsb, d);
      sum += d;
      ++samples;
    }
  }
  e.mean_lsb = samples ? sum / static_cast<double>(samples) : 0.0;
  return e;
}

}  // namespace

ErrorBudget error_budget(const ExploreScenes& scenes, std::size_t scene, const UnitConfig& config) {
  config.validate();
  const HostSetup& h = scenes.setup(scene, config.out_bits);
  const PreparedFrame& f = h.frame;
  ShadingVariant function;
  for (const Material& m : f.scene.materials)
    function.specular.push_back(unit_float_function(config, m.exponent));
  ShadingVariant taylor = function;
  taylor.quadratics = &f.setup.series;
  const int ch = config.channels;
  const ReferenceImage exact_fn =
      render_variant(f.setup.triangles, f.visibility, f.scene, ch, function);
  const ReferenceImage quad_fn =
      render_variant(f.setup.triangles, f.visibility, f.scene, ch, taylor);
  const EncodedFrame enc = encode_frame(f.scene, config, f.setup, f.visibility);
  const std::vector<PixelOut> pixels = ShadeUnit(config).run(enc.stream);

  ErrorBudget b;
  b.scene = scenes.paths()[scene];
  b.function = image_difference(exact_fn, h.reference, f.visibility.owner, config.out_bits);
  b.taylor = image_difference(quad_fn, exact_fn, f.visibility.owner, config.out_bits);
  b.quantization = model_difference(pixels, quad_fn, config.out_bits);
  b.total = model_difference(pixels, h.reference, config.out_bits);
  return b;
}

}  // namespace shadesim
