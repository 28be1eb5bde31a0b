// Design-space exploration: width sweeps of the bit-accurate model against error, cycles per
// pixel and area, the cheapest widths that meet an error budget, and the error split by source.
//
// Host setup (projection, Taylor setup, visibility, the double reference) depends only on the
// scene and the output width, so it is done once per (scene, out_bits); a width point only
// re-encodes the command stream (quantizes the coefficients) and re-runs the model and the
// cycle model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/frame.h"
#include "host/metrics.h"
#include "host/reference.h"
#include "model/unit_config.h"

namespace shadesim {

// Area of one configuration, as the area model (sim/engines/area_report.h) reports it. An
// AreaFunction is called from the worker threads at once: it must be safe to call concurrently.
struct AreaFigure {
  double cells = 0;    // the figure the search minimises
  double lut4 = 0;     // iCE40 LUT4s, where the area model gives them (else 0)
  std::string metric;  // what `cells` counts and how it was obtained (measured or estimated)
};
using AreaFunction = std::function<AreaFigure(const UnitConfig&)>;

// One scene's host setup at one output width, shared read-only by every point using it.
struct HostSetup {
  PreparedFrame frame;
  ReferenceImage reference;
};

// The scenes of an exploration and their host setups, keyed by output width.
class ExploreScenes {
 public:
  // Prepares every scene on `start` (a unit that fits all of them: fixed structure). Throws
  // SceneError / std::invalid_argument naming the scene for bad input.
  ExploreScenes(std::vector<std::string> paths, const UnitConfig& start,
                std::optional<double> setup_budget_lsb, int max_depth);

  const std::vector<std::string>& paths() const { return paths_; }
  // Sets up every scene for out_bits unless done already. Not thread-safe: call before a batch.
  void prepare(int out_bits);
  // Requires prepare(out_bits) first.
  const HostSetup& setup(std::size_t scene, int out_bits) const;

 private:
  std::vector<std::string> paths_;
  UnitConfig start_;
  std::optional<double> setup_budget_lsb_;
  int max_depth_;
  std::map<int, std::vector<std::shared_ptr<const HostSetup>>> by_out_bits_;
};

// The figures of one configuration over all scenes.
struct PointFigures {
  // Over all scenes: max of the maxima, pixel-weighted means, PSNR of the pooled squared error.
  ErrorStats error;
  uint64_t pixels = 0, cycles = 0;
  double cycles_per_pixel = 0;
  AreaFigure area;
  std::size_t coefficients_out_of_range = 0;
};

// Evaluates `config` on every scene (prepare(config.out_bits) first). Thread-safe.
PointFigures evaluate_point(const ExploreScenes& scenes, const UnitConfig& config,
                            const AreaFunction& area);

// One knob the sweep varies (a width or a structural choice): its stage, its candidate values
// (narrowest / cheapest first) and how a value is written into a configuration.
struct Knob {
  std::string stage;  // coefficients | series | specular | specular colour | span setup |
                      // diffuse colour | pipelining | output
  std::string name;   // e.g. "series.frac"
  std::vector<int> values;
  std::vector<std::string> labels;  // parallel to values: how a value prints
  std::function<void(UnitConfig&, int)> apply;
  std::function<int(const UnitConfig&)> read;
  // false: swept for the table and the front only (output bits are what was asked for; the
  // structure trades area against cycles and clock, which the error search does not weigh)
  bool searched = true;
  bool choice = false;  // a choice (trn/rnd, wrap/sat), not a width: "wider" means the start's
};

// The knobs for `start` (explore/explore_knobs.cpp): coefficient integer and fraction bits; series
// fraction and integer bits, truncate/round, wrap/saturate; the selected specular unit's widths
// and its output fraction bits; specular colour fraction bits; with `structure`, the structure,
// not searched: span setup site, the host's start depth, the diffuse colour (where the start has
// colour or multiplies), the pipelining ladder's rungs (pipelining_ladder); output bits (not
// searched).
std::vector<Knob> knobs_for(const UnitConfig& start, bool structure = true);

// A point's unit as Yosys measured it (shadesim area), for the points explore calls
// Pareto-optimal: the sweep itself runs on AreaFunction's estimates.
struct MeasuredArea {
  double cells = 0;  // generic cells, the same metric as AreaFigure::cells
  double gate_equivalents = 0;
  double lut4 = 0;
  bool fits_hx8k = false;
  std::optional<double> fmax_mhz;  // nextpnr-ice40, out of context; none where it does not fit
  int64_t logic_depth = -1;        // gate levels on the longest path (Yosys ltp)
  std::string note;                // why there is no Fmax
  std::string critical_path;       // nextpnr's post-route one, "net A -> net B (...)"; or empty
  // The unit on a standard-cell library (osu018 unless told otherwise), timed by OpenSTA
  // (sim/eda/sta/liberty_flow.h); none where that flow was not run.
  std::string library;                     // "osu018", else the liberty's library name
  std::optional<double> library_fmax_mhz;  // 1000 / (analysis period - worst slack)
  std::optional<double> library_area_um2;  // table RAM macros apart
  std::string library_critical_path;       // "from -> to" (registers' Q nets or ports)
};
using MeasureFunction = std::function<MeasuredArea(const UnitConfig&)>;

struct ExplorePoint {
  UnitConfig config;
  std::string phase;               // start | stage | joint
  std::string stage, knob, value;  // what this point changed from the start ("" for start/joint)
  PointFigures figures;
  bool valid = true;  // false: the configuration does not validate (figures empty)
  std::string invalid_reason;
  bool meets_budget = false;
  bool pareto = false;  // on the front of (max LSB, mean LSB) against area and throughput
  std::optional<MeasuredArea> measured;  // Yosys's figures (measure_front), else none
  // The area the front is drawn with: the measurement where there is one, else the estimate.
  double front_area() const { return measured ? measured->cells : figures.area.cells; }
  // Mpixel/s at the measured Fmax (Fmax x pixels per clock), where both are known.
  std::optional<double> mpixel_per_s() const;
  // The same at the library's Fmax.
  std::optional<double> library_mpixel_per_s() const;
};

struct ExploreOptions {
  double budget_lsb = 1.0;  // max |code - reference code| over all pixels and channels
  int jobs = 2;             // worker threads for the points
  // false: the widths alone (explore --widths-only); each structural point the sweep adds can
  // join the front, and each point on the front costs a synthesis when the front is measured.
  bool structure = true;
};

// Called from worker threads (serialised) after each point: phase, points done, points in the
// phase so far known.
using ExploreProgress =
    std::function<void(const std::string& phase, std::size_t done, std::size_t total)>;

struct ExploreResult {
  UnitConfig start;
  std::vector<ExplorePoint> points;  // every point evaluated, start first
  std::size_t start_index = 0;
  std::optional<std::size_t> chosen;  // the joint refinement's result, when it meets the budget
  std::vector<std::string> log;       // the search's steps, one line each
};

// The search, as `explore --help` states it:
//  1. every knob's values alone, the other knobs at the start configuration (per-stage sweep);
//     each searched knob's minimum is its cheapest value meeting the budget (else its start);
//  2. joint refinement: all per-stage minima combined; while that breaks the budget, try each
//     knob one step wider (numeric knobs the next value, choices back to the start's) and keep
//     the step that buys the most error reduction (max real LSB, then mean) per area added;
//  3. the Pareto front over every evaluated point.
ExploreResult explore(ExploreScenes& scenes, const UnitConfig& start, const AreaFunction& area,
                      const ExploreOptions& options, const ExploreProgress& progress = {});

// Marks `pareto` on the points not dominated in (max code LSB, mean code LSB, area, throughput):
// a point is dominated when another is no worse in all four and better in one. Only points with
// `out_bits` output bits take part: an LSB of another output width is another unit. Area is
// front_area(): measured where measured. Throughput is Mpixel/s where both points have a measured
// Fmax (the library's, else both iCE40's), else cycles per pixel between points of one
// pipelining (pipelining_of); otherwise the two are not ordered on it: a pipeline register buys
// clock for its cycle of latency, which only a measured Fmax shows.
void mark_pareto(std::vector<ExplorePoint>& points, int out_bits);

// Yosys for the front: measures every Pareto point (and the chosen one) not measured yet, marks
// the front again with the measured areas, and repeats until every point on it is measured (a
// point the estimate kept off the front may join it once a neighbour's true area is known).
// `progress` is told each point before it is measured. Returns the number measured.
using MeasureProgress = std::function<void(std::size_t index, std::size_t done, std::size_t total)>;
std::size_t measure_front(ExploreResult& result, const MeasureFunction& measure,
                          const MeasureProgress& progress = {});

// How far the estimates were from Yosys on the measured points: |estimate / measured - 1| of
// generic cells, median and max, in percent; count 0 when none was measured.
struct EstimateError {
  std::size_t count = 0;
  double median_pct = 0, max_pct = 0;
};
EstimateError estimate_error(const ExploreResult& result);

// The error of one configuration on one scene split by source, in output LSBs before rounding:
//   function     exact cosines through the unit's double function vs the reference (exact pow)
//   taylor       the setup's quadratics through that function vs exact cosines through it
//   quantization the bit-accurate model vs the quadratics through the function in double
//                (includes the output rounding, up to 0.5 LSB)
//   total        the model vs the reference; per pixel total <= function + taylor + quantization
// Only `quantization` responds to the widths explore sweeps; `function` is the choice of unit
// (and its fitted parameter), `taylor` the setup budget (subdivision).
struct ErrorPart {
  double max_lsb = 0, mean_lsb = 0;
};
struct ErrorBudget {
  std::string scene;
  ErrorPart function, taylor, quantization, total;
};
ErrorBudget error_budget(const ExploreScenes& scenes, std::size_t scene, const UnitConfig& config);

}  // namespace shadesim
