// The engine of shadesim merge DIR... (its options: sim/cli/merge.cpp): the regression that shards,
// job lines or resumed runs wrote into one or more output folders, reported as one `regress` would:
// the same table, JSON and JUnit. What the folders' plans name but no folder holds a result for is
// reported as missing (started and never finished, or never started), a run found in two folders as
// a duplicate, an unreadable result by its file; any of them makes the merge fail. Folder layout:
// sim/regress/regress_results.h.
#include "sim/regress/merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "sim/regress/regress_results.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

struct Planned {
  RunSpec spec;
  std::string plan;  // the plan file that names it
};

std::vector<fs::path> json_files(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// What the folders hold: every planned run, every result, and what is wrong with them.
struct Gathered {
  std::vector<std::string> problems;
  std::map<std::string, Planned> planned;         // id -> the first plan naming it
  std::map<std::string, RunRecord> found;         // id -> its record
  std::map<std::string, std::string> found_at;    // id -> its run.json
  std::map<std::string, std::string> unfinished;  // id -> a run folder without run.json
};

void read_plans(const fs::path& dir, Gathered& g) {
  for (const auto& f : json_files(dir / "plans")) {
    try {
      std::ifstream is(f);
      const nlohmann::json j = nlohmann::json::parse(is);
      if (!j.is_object() || !j.contains("runs") || !j.at("runs").is_array()) {
        throw std::runtime_error(f.string() + ": expected a regress plan with a runs array");
      }
      for (size_t i = 0; i < j.at("runs").size(); ++i) {
        const RunSpec s =
            spec_from_json(j.at("runs")[i], f.string() + ": runs[" + std::to_string(i) + "]");
        g.planned.emplace(s.id(), Planned{s, f.string()});
      }
    } catch (const nlohmann::json::exception& e) {
      g.problems.push_back("malformed plan " + f.string() + ": not valid JSON (" + e.what() + ")");
    } catch (const std::exception& e) {
      g.problems.push_back(std::string("malformed plan ") + e.what());
    }
  }
}

void read_results(const fs::path& dir, Gathered& g) {
  if (!fs::is_directory(dir / "runs")) return;
  std::vector<fs::path> run_dirs;
  for (const auto& e : fs::directory_iterator(dir / "runs")) {
    if (e.is_directory()) run_dirs.push_back(e.path());
  }
  std::sort(run_dirs.begin(), run_dirs.end());
  for (const auto& rd : run_dirs) {
    const std::string id = rd.filename().string();
    const fs::path file = rd / "run.json";
    if (!fs::exists(file)) {
      g.unfinished.emplace(id, rd.string());
      continue;
    }
    RunRecord r;
    try {
      r = read_run_record(file.string());
    } catch (const std::exception& e) {
      g.problems.push_back(std::string("malformed result ") + e.what());
      g.found_at.emplace(id, file.string());  // reported: not missing as well
      continue;
    }
    if (r.spec.id() != id) {
      g.problems.push_back("result " + file.string() + " is of run " + r.spec.id() +
                           ", not of its folder's " + id);
      continue;
    }
    if (g.found_at.count(id)) {
      g.problems.push_back("duplicate run " + id + ": " + g.found_at.at(id) + " and " +
                           file.string() + " (the first is reported)");
      continue;
    }
    g.found_at.emplace(id, file.string());
    g.found.emplace(id, r);
  }
}

Gathered gather(const std::vector<std::string>& dirs) {
  Gathered g;
  for (const auto& d : dirs) {
    const fs::path dir(d);
    if (!fs::is_directory(dir)) throw std::invalid_argument("merge: " + d + ": no such folder");
    if (!fs::is_directory(dir / "plans") && !fs::is_directory(dir / "runs")) {
      throw std::invalid_argument(
          "merge: " + d + ": not a regress output folder (it has neither plans/ nor runs/)");
    }
    read_plans(dir, g);
    read_results(dir, g);
  }
  return g;
}

// A planned run without a result, with why: never started, prepared but stopped, or killed.
RunRecord missing_run(const Planned& p, const std::map<std::string, std::string>& unfinished) {
  RunRecord r;
  r.spec = p.spec;
  r.scene_name = scene_label(p.spec.scene);
  r.status = "missing";
  const auto u = unfinished.find(p.spec.id());
  r.message = "planned in " + p.plan + ", but no folder holds its result: " +
              (u == unfinished.end() ? std::string("never started")
               // regress prepares every run's folder (its stream) before any runs; a run that
               // started has its simulator's log there.
               : fs::exists(fs::path(u->second) / "cosim.log")
                   ? u->second + " has no run.json (started, never finished: killed?)"
                   : u->second + " was prepared but its run never started (the job was stopped)");
  if (u != unfinished.end()) r.dir = u->second;
  return r;
}

void print_merge_summary(const MergeOptions& o, const Gathered& g,
                         const std::vector<RunRecord>& records, const RunCounts& c) {
  std::cout << "\nmerge: " << records.size() << " run(s) from " << o.dirs.size()
            << " folder(s): " << c.passed << " passed, " << c.mismatched << " mismatched, "
            << c.hangs << " hung, " << c.timeouts << " timed out, " << c.errors << " error(s), "
            << c.skipped << " skipped, " << c.missing << " missing, " << c.interrupted
            << " interrupted (--resume runs them)\n";
  for (const auto& r : records) {
    if (r.status != "pass" && r.status != "skipped") {
      std::cout << "  " << r.status << ": " << r.spec.id() << ": " << r.message
                << (r.replay.empty() ? "" : "\n    replay: " + r.replay) << '\n';
    }
  }
  for (const auto& p : g.problems) std::cout << "  " << p << '\n';
  for (const auto& [id, r] : g.found) {
    if (!g.planned.empty() && !g.planned.count(id)) {
      std::cout << "  note: " << id << " (" << g.found_at.at(id)
                << ") is in no plan of these folders: an earlier regress into the same folder? It "
                   "is reported.\n";
    }
  }
}

}  // namespace

int run_merge(const MergeOptions& o) {
  Gathered g = gather(o.dirs);
  std::vector<RunRecord> records;
  for (const auto& [id, r] : g.found) records.push_back(r);
  std::vector<std::string> missing;
  for (const auto& [id, p] : g.planned) {
    if (g.found_at.count(id)) continue;
    missing.push_back(id);
    records.push_back(missing_run(p, g.unfinished));
  }
  sort_records(records);
  check_backends_agree(records);
  print_run_table(records);
  const RunCounts c = count_runs(records);
  if (g.planned.empty())
    g.problems.push_back("no plan in any folder: missing runs cannot be named");
  print_merge_summary(o, g, records, c);
  if (!o.junit_path.empty()) write_junit_report(o.junit_path, records);
  if (!o.json_path.empty()) {
    write_json_report(
        o.json_path, records,
        {{"merged_from", o.dirs}, {"missing_runs", missing}, {"problems", g.problems}});
  }
  if (records.empty()) {
    std::cout << "merge: FAIL: no run found\n";
    return 1;
  }
  if (!g.problems.empty() || c.failed()) {
    std::cout << "merge: FAIL"
              << (missing.empty() ? "" : ": " + std::to_string(missing.size()) + " run(s) missing")
              << '\n';
    return 1;
  }
  return 0;
}

}  // namespace shadesim
