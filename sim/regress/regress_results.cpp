#include "sim/regress/regress_results.h"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "model/text_file.h"
#include "sim/regress/junit.h"

namespace shadesim {

namespace fs = std::filesystem;

std::string file_label(const std::string& config) {
  std::string s = config;
  if (fs::path(s).extension() == ".json") s = fs::path(s).stem().string();
  for (char& c : s) {
    if (c == '/' || c == ':' || c == ' ') c = '_';
  }
  return s;
}

bool is_random_scene(const std::string& scene) { return scene.rfind(kRandomScenePrefix, 0) == 0; }

std::string random_scenario(const std::string& scene) {
  return is_random_scene(scene) ? scene.substr(std::string(kRandomScenePrefix).size()) : "";
}

std::string scene_label(const std::string& scene) {
  return is_random_scene(scene) ? "random-" + random_scenario(scene)
                                : fs::path(scene).stem().string();
}

std::string RunSpec::id() const {
  return scene_label(scene) + "__" + file_label(config) + "__" + backend + "__seed" +
         std::to_string(seed);
}

nlohmann::json spec_json(const RunSpec& s) {
  return {{"id", s.id()},       {"scene", s.scene},     {"config_kind", s.config_kind},
          {"config", s.config}, {"backend", s.backend}, {"seed", s.seed}};
}

namespace {

// A required field of the given JSON type, or an error naming where it is and what was expected.
template <typename T>
T required(const nlohmann::json& j, const char* key, const std::string& where,
           const char* expected) {
  if (!j.is_object()) throw std::runtime_error(where + ": expected a JSON object");
  if (!j.contains(key))
    throw std::runtime_error(where + ": field '" + key + "' is missing (expected " + expected +
                             ")");
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::runtime_error(where + ": field '" + key + "' is " + j.at(key).dump() +
                             ", expected " + expected);
  }
}

// An optional field, `fallback` when absent or null; a present value of the wrong type is an error.
template <typename T>
T optional(const nlohmann::json& j, const char* key, T fallback, const std::string& where,
           const char* expected) {
  if (!j.contains(key) || j.at(key).is_null()) return fallback;
  return required<T>(j, key, where, expected);
}

const std::vector<std::string>& known_statuses() {
  static const std::vector<std::string> s = {"pass",  "mismatch", "hang",        "timeout",
                                             "error", "skipped",  "interrupted", "missing"};
  return s;
}

}  // namespace

RunSpec spec_from_json(const nlohmann::json& j, const std::string& where) {
  RunSpec s;
  s.scene = required<std::string>(j, "scene", where, "a scene path");
  s.config_kind = required<std::string>(j, "config_kind", where, "own, default, named or file");
  if (s.config_kind != "own" && s.config_kind != "default" && s.config_kind != "named" &&
      s.config_kind != "file") {
    throw std::runtime_error(where + ": field 'config_kind' is '" + s.config_kind +
                             "', expected own, default, named or file");
  }
  s.config = required<std::string>(j, "config", where, "a configuration name or file");
  s.backend = required<std::string>(j, "backend", where, "cpp or systemc");
  if (s.backend != "cpp" && s.backend != "systemc") {
    throw std::runtime_error(where + ": field 'backend' is '" + s.backend +
                             "', expected cpp or systemc");
  }
  s.seed = required<uint64_t>(j, "seed", where, "an unsigned seed");
  if (j.contains("id") && j.at("id") != s.id()) {
    throw std::runtime_error(where + ": field 'id' is " + j.at("id").dump() +
                             ", but scene, config, backend and seed make " + s.id());
  }
  return s;
}

nlohmann::json record_json(const RunRecord& r) {
  nlohmann::json j = spec_json(r.spec);
  j["scene_name"] = r.scene_name;
  j["unit"] = r.unit;
  j["unit_text"] = r.unit_text;
  j["status"] = r.status;
  j["pixels"] = r.pixels;
  j["cycles"] = r.cycles;
  j["cycles_per_pixel"] =
      r.pixels ? static_cast<double>(r.cycles) / static_cast<double>(r.pixels) : 0.0;
  j["seconds"] = r.seconds;
  j["cycles_per_second"] = r.cycles_per_second;
  j["message"] = r.message;
  j["replay"] = r.replay;
  j["dir"] = r.dir;
  j["stream"] = r.stream;
  j["log"] = r.log;
  j["waves"] = r.waves;
  return j;
}

RunRecord read_run_record(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw std::runtime_error(path + ": cannot open");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
  }
  RunRecord r;
  r.spec = spec_from_json(j, path);
  r.scene_name =
      optional<std::string>(j, "scene_name", scene_label(r.spec.scene), path, "a string");
  r.unit = j.contains("unit") ? j.at("unit") : nlohmann::json();
  r.unit_text = optional<std::string>(j, "unit_text", "", path, "a string");
  r.status = required<std::string>(j, "status", path,
                                   "pass, mismatch, hang, timeout, error, skipped or interrupted");
  if (std::find(known_statuses().begin(), known_statuses().end(), r.status) ==
      known_statuses().end()) {
    throw std::runtime_error(
        path + ": field 'status' is '" + r.status +
        "', expected pass, mismatch, hang, timeout, error, skipped or interrupted");
  }
  r.pixels = required<uint64_t>(j, "pixels", path, "an unsigned pixel count");
  r.cycles = required<uint64_t>(j, "cycles", path, "an unsigned cycle count");
  r.seconds = optional<double>(j, "seconds", 0.0, path, "a number");
  r.cycles_per_second = optional<double>(j, "cycles_per_second", 0.0, path, "a number");
  r.message = optional<std::string>(j, "message", "", path, "a string");
  r.replay = optional<std::string>(j, "replay", "", path, "a string");
  r.dir = optional<std::string>(j, "dir", fs::path(path).parent_path().string(), path, "a string");
  r.stream = optional<std::string>(j, "stream", "", path, "a string");
  r.log = optional<std::string>(j, "log", "", path, "a string");
  r.waves = optional<std::string>(j, "waves", "", path, "a string");
  return r;
}

void write_file_atomically(const std::string& path, const std::string& text) {
  const fs::path target(path);
  if (!target.parent_path().empty()) fs::create_directories(target.parent_path());
  // Unique per process and host: a shared folder may have writers on several machines.
  char host[256] = {0};
  gethostname(host, sizeof host - 1);
  const fs::path tmp = target.string() + ".tmp." + host + "." + std::to_string(getpid());
  write_text_file(tmp.string(), text);
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error(path +
                             ": cannot rename the finished temp file into place: " + ec.message());
  }
}

void check_backends_agree(std::vector<RunRecord>& records) {
  for (size_t a = 0; a < records.size(); ++a) {
    for (size_t b = a + 1; b < records.size(); ++b) {
      RunRecord& x = records[a];
      RunRecord& y = records[b];
      if (x.spec.scene == y.spec.scene && x.spec.config == y.spec.config &&
          x.spec.seed == y.spec.seed && x.status == "pass" && y.status == "pass" &&
          x.cycles != y.cycles) {
        y.status = "mismatch";
        y.message = "backends disagree: " + x.spec.backend + " " + std::to_string(x.cycles) +
                    " cycles, " + y.spec.backend + " " + std::to_string(y.cycles);
      }
    }
  }
}

void sort_records(std::vector<RunRecord>& records) {
  std::stable_sort(records.begin(), records.end(), [](const RunRecord& a, const RunRecord& b) {
    return std::tie(a.spec.scene, a.spec.config, a.spec.backend, a.spec.seed) <
           std::tie(b.spec.scene, b.spec.config, b.spec.backend, b.spec.seed);
  });
}

RunCounts count_runs(const std::vector<RunRecord>& records) {
  RunCounts c;
  for (const auto& r : records) {
    if (r.status == "pass")
      ++c.passed;
    else if (r.status == "mismatch")
      ++c.mismatched;
    else if (r.status == "hang")
      ++c.hangs;
    else if (r.status == "timeout")
      ++c.timeouts;
    else if (r.status == "skipped")
      ++c.skipped;
    else if (r.status == "missing")
      ++c.missing;
    else if (r.status == "interrupted")
      ++c.interrupted;
    else
      ++c.errors;
  }
  return c;
}

namespace {

// Column width: the longest entry (at least the header), so long names never run together.
template <typename F>
int column_width(const std::vector<RunRecord>& records, const std::string& header, F get) {
  size_t w = header.size();
  for (const auto& r : records) w = std::max(w, get(r).size());
  return static_cast<int>(w + 2);
}

}  // namespace

void print_run_table(const std::vector<RunRecord>& records) {
  const int ws = column_width(records, "scene", [](const RunRecord& r) { return r.scene_name; });
  const int wc = column_width(records, "config", [](const RunRecord& r) { return r.spec.config; });
  // {fmt}: the widths are the longest entries', so long build names never run together.
  const auto row = [&](const auto& scene, const auto& config, const auto& backend, const auto& seed,
                       const auto& pixels, const auto& cycles, const auto& per_pixel,
                       const auto& result, const auto& wall, const auto& rate) {
    fmt::print("{:<{}}{:<{}}{:<9}{:>6}{:>9}{:>11}{:>8}{:>10}{:>9}{:>11}\n", scene, ws, config, wc,
               backend, seed, pixels, cycles, per_pixel, result, wall, rate);
  };
  std::cout << '\n' << std::flush;
  row("scene", "config", "backend", "seed", "pixels", "cycles", "cyc/px", "result", "wall s",
      "Mcycles/s");
  for (const auto& r : records) {
    // Only a completed run has a cycle count; a mismatch stops the run where it is found.
    const bool complete = r.status == "pass";
    const std::string per_pixel =
        complete && r.pixels
            ? fmt::format("{:.3f}", static_cast<double>(r.cycles) / static_cast<double>(r.pixels))
            : "-";
    row(r.scene_name, r.spec.config, r.spec.backend, r.spec.seed, r.pixels,
        complete ? std::to_string(r.cycles) : "-", per_pixel, r.status,
        fmt::format("{:.2f}", r.seconds),
        complete ? fmt::format("{:.2f}", r.cycles_per_second / 1e6) : "-");
  }
  // What each configuration is.
  std::vector<std::string> seen;
  fmt::print("\nconfigurations:\n");
  for (const auto& r : records) {
    if (r.unit_text.empty() || std::find(seen.begin(), seen.end(), r.spec.config) != seen.end())
      continue;
    seen.push_back(r.spec.config);
    fmt::print("  {:<{}}{}\n", r.spec.config, wc, r.unit_text);
  }
  std::fflush(stdout);
}

void write_json_report(const std::string& path, const std::vector<RunRecord>& records,
                       nlohmann::json extra) {
  const RunCounts c = count_runs(records);
  nlohmann::json all = nlohmann::json::array();
  for (const auto& r : records) all.push_back(record_json(r));
  nlohmann::json doc = std::move(extra);
  doc["passed"] = c.passed;
  doc["mismatched"] = c.mismatched + c.hangs;
  doc["errors"] = c.errors + c.timeouts + c.missing + c.interrupted;
  doc["skipped"] = c.skipped;
  doc["hangs"] = c.hangs;
  doc["timeouts"] = c.timeouts;
  doc["missing"] = c.missing;
  doc["interrupted"] = c.interrupted;
  doc["jobs"] = all;
  write_text_file(path, doc.dump(2) + '\n');
}

void write_junit_report(const std::string& path, const std::vector<RunRecord>& records) {
  JUnitSuite suite{"shadesim.regress", {}};
  for (const auto& r : records) {
    JUnitCase c;
    c.classname = "regress." + r.scene_name;
    c.name = r.spec.config + "." + r.spec.backend + ".seed" + std::to_string(r.spec.seed);
    c.seconds = r.seconds;
    if (r.status == "skipped") {
      c.skipped = r.message;
    } else if (r.status != "pass") {
      c.failure = r.status + ": " + r.message + (r.replay.empty() ? "" : "\nreplay: " + r.replay);
    }
    suite.cases.push_back(c);
  }
  write_junit(path, suite);
}

}  // namespace shadesim
