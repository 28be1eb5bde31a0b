// Results of `shadesim regress` runs, shared by regress (which writes them as each run ends) and
// `shadesim merge` (which reads them back from many folders): one record per run, its file
// format, and the summary table, JSON and JUnit both commands print from a list of records.
//
// An output folder holds
//   plans/<name>.json      what a regress process was asked to run (written before any run)
//   runs/<id>/run.json     one finished run's record (temp file, then rename: never half written)
//   runs/<id>/...          that run's stream, unit, co-simulation log and result, failing streams
// A run's id names its scene, configuration, backend and seed: sphere__own_sphere__cpp__seed1.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace shadesim {

// A random run's `scene`: this prefix and the co-simulation scenario's name (random:edge). Its
// stream is sim/harness/random_stream.h's for the run's unit and seed.
constexpr const char* kRandomScenePrefix = "random:";
bool is_random_scene(const std::string& scene);
std::string random_scenario(const std::string& scene);  // "edge" for random:edge
// The scene's name in ids, tables and JUnit: its stem, or random-<scenario> for a random run.
std::string scene_label(const std::string& scene);

// What one run is: enough to plan it again in another process (regress --resume, a job line).
struct RunSpec {
  std::string scene;        // path, as given, or random:<scenario>
  std::string config_kind;  // "own" (the scene's own unit), "default", "named" or "file"
  std::string config;       // own:<scene>, default, a named build, or a UnitConfig file's path
  std::string backend;      // cpp | systemc
  uint64_t seed = 0;
  std::string id() const;
};

nlohmann::json spec_json(const RunSpec& s);
// Throws std::runtime_error naming `where` and the field.
RunSpec spec_from_json(const nlohmann::json& j, const std::string& where);

// A configuration's name as part of a file name (a config file's path has folders in it).
std::string file_label(const std::string& config);

// Statuses: pass | mismatch | hang (the watchdog: the RTL stopped producing pixels) | timeout
// (killed after --timeout) | error (could not run, or the co-simulation failed) | skipped (the
// scene does not fit the configuration) | missing (merge: planned, no result).
struct RunRecord {
  RunSpec spec;
  std::string scene_name;  // the scene's stem
  std::string unit_text;   // the unit in one line, with its injected faults (and
                           // for own: derived or a cached derivation)
  nlohmann::json unit;     // config_to_json of the unit (null when it could not be made)
  std::string status = "pending";
  std::string message;
  std::string replay;
  uint64_t pixels = 0, cycles = 0;
  double seconds = 0, cycles_per_second = 0;
  std::string dir;  // the run's folder
  std::string stream, log, waves;
};

nlohmann::json record_json(const RunRecord& r);
// Reads a run.json; throws std::runtime_error naming the file and what is wrong.
RunRecord read_run_record(const std::string& path);
// `text` into `path` through a temp file in the same folder and a rename, so a reader (or a
// killed writer) never sees half a file.
void write_file_atomically(const std::string& path, const std::string& text);

// Both backends simulate the same RTL on the same stimulus: their cycle counts must agree. Marks
// the later run a mismatch when they do not.
void check_backends_agree(std::vector<RunRecord>& records);
// Report order: scene, configuration, backend, seed.
void sort_records(std::vector<RunRecord>& records);

struct RunCounts {
  long passed = 0, mismatched = 0, hangs = 0, timeouts = 0, errors = 0, skipped = 0, missing = 0;
  long interrupted = 0;  // not run, or stopped, because the job got SIGINT / SIGTERM
  bool failed() const {
    return mismatched > 0 || hangs > 0 || timeouts > 0 || errors > 0 || missing > 0 ||
           interrupted > 0;
  }
};
RunCounts count_runs(const std::vector<RunRecord>& records);

void print_run_table(const std::vector<RunRecord>& records);
// {passed, mismatched, errors, skipped, hangs, timeouts, missing, seed?, jobs: [...]} plus `extra`;
// mismatched counts hangs too, errors counts timeouts, missing and interrupted runs (so a reader
// that knows only the first four still sees every failure).
void write_json_report(const std::string& path, const std::vector<RunRecord>& records,
                       nlohmann::json extra);
void write_junit_report(const std::string& path, const std::vector<RunRecord>& records);

}  // namespace shadesim
