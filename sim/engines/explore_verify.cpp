#include "sim/engines/explore_verify.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "sim/eda/common/process.h"
#include "sim/eda/common/shell.h"

namespace shadesim {

void emit_verify_jobs(const std::vector<PointToVerify>& points,
                      const std::vector<std::string>& scenes, const std::string& out_dir,
                      const std::string& jobs_file) {
  const std::filesystem::path self = self_executable("--emit-jobs");
  std::ofstream all(jobs_file);
  if (!all) throw std::runtime_error("--emit-jobs " + jobs_file + ": cannot open for writing");
  size_t lines = 0;
  std::string dirs;
  for (const auto& p : points) {
    const std::filesystem::path dir = std::filesystem::path(out_dir) / "verify" / p.name;
    std::filesystem::create_directories(dir);
    const std::string part = (dir / "jobs.txt").string(), log = (dir / "emit.log").string();
    std::vector<std::string> args = {self.string(), "regress"};
    args.insert(args.end(), scenes.begin(), scenes.end());
    args.insert(args.end(),
                {"--config", p.config_file, "--out", dir.string(), "--emit-jobs", part});
    if (run_process(args, log).exit_code != 0) {
      throw std::runtime_error("--emit-jobs: shadesim regress --emit-jobs for " + p.name +
                               " failed (log: " + log + ")");
    }
    std::ifstream is(part);
    for (std::string line; std::getline(is, line);) {
      all << line << '\n';
      ++lines;
    }
    dirs += " " + dir.string();
  }
  if (!all) throw std::runtime_error("--emit-jobs " + jobs_file + ": write failed");
  std::cout << "jobs         " << lines << " regress run(s) of the verification in " << jobs_file
            << "; run them (parallel < " << jobs_file << "), then shadesim merge" << dirs << "\n";
}

std::vector<Verification> verify_in_rtl(const std::vector<PointToVerify>& points,
                                        const std::vector<std::string>& scenes,
                                        const std::string& out_dir) {
  const std::filesystem::path self = self_executable("--verify");
  std::vector<Verification> out;
  for (const auto& p : points) {
    Verification v;
    v.name = p.name;
    const std::filesystem::path dir = std::filesystem::path(out_dir) / "verify" / p.name;
    std::filesystem::create_directories(dir);
    v.report = (dir / "regress.json").string();
    v.log = (dir / "regress.log").string();
    std::vector<std::string> args = {self.string(), "regress"};
    args.insert(args.end(), scenes.begin(), scenes.end());
    args.insert(args.end(), {"--config", p.config_file, "--out", dir.string(), "--json", v.report,
                             "--junit", (dir / "junit.xml").string()});
    std::cerr << "verify: " << p.name << " in RTL (shadesim regress ... --config " << p.config_file
              << "; log " << v.log << ")" << std::endl;
    const ProcessResult r = run_process(args, v.log);
    std::ifstream is(v.report);
    nlohmann::json j;
    try {
      if (is) j = nlohmann::json::parse(is);
    } catch (const nlohmann::json::exception&) {
    }
    if (j.is_object()) {
      v.passed = j.value("passed", 0L);
      v.mismatched = j.value("mismatched", 0L);
      v.errors = j.value("errors", 0L);
      v.skipped = j.value("skipped", 0L);
    }
    v.verified =
        r.exit_code == 0 && v.passed > 0 && v.mismatched == 0 && v.errors == 0 && v.skipped == 0;
    out.push_back(v);
  }
  return out;
}

nlohmann::json verification_json(const std::vector<Verification>& verified) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& v : verified) {
    j.push_back({{"name", v.name},
                 {"verified", v.verified},
                 {"passed", v.passed},
                 {"mismatched", v.mismatched},
                 {"errors", v.errors},
                 {"skipped", v.skipped},
                 {"regress_json", v.report},
                 {"log", v.log}});
  }
  return j;
}

}  // namespace shadesim
