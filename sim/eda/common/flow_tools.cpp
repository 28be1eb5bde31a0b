#include "sim/eda/common/flow_tools.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <future>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/common/process.h"
#include "sim/eda/common/rtl_files.h"

namespace shadesim::flow_tools {

void write_atomically(const fs::path& p, const std::string& text) {
  // A unique temporary name in the same folder, then rename(2): readers see all or nothing.
  const fs::path tmp = p.string() + ".tmp." + std::to_string(::getpid()) + "." +
                       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
  write_text_file(tmp.string(), text);
  std::error_code ec;
  fs::rename(tmp, p, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error(p.string() + ": cannot rename into place: " + ec.message());
  }
}

std::string find_tool(const std::string& name, const std::string& package) {
  auto executable = [](const fs::path& p) {
    return ::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p);
  };
  if (name.find('/') != std::string::npos) {
    if (executable(name)) return name;
  } else if (const char* path = std::getenv("PATH")) {
    std::stringstream ss(path);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
      if (dir.empty()) continue;
      const fs::path p = fs::path(dir) / name;
      if (executable(p)) return p.string();
    }
  }
  throw MissingToolError(
      "'" + name + "' not found" + (name.find('/') != std::string::npos ? "" : " on PATH") +
      ": shadesim area needs it (Debian package " + package + "; scripts/setup installs it)");
}

std::string tool_version(const std::string& program, const std::vector<std::string>& args) {
  std::vector<std::string> argv = {program};
  argv.insert(argv.end(), args.begin(), args.end());
  return first_line(run_process(argv, "").output);
}

std::vector<fs::path> rtl_sources(const std::string& dir) {
  // The one list (rtl/files.f); a tree from before it (--rtl-dir) is read whole, below.
  if (fs::exists(fs::path(dir) / "files.f")) return rtl_file_list(dir);
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file() && e.path().extension() == ".sv") files.push_back(e.path());
  }
  if (ec) throw std::runtime_error(dir + ": cannot list the RTL sources: " + ec.message());
  if (files.empty()) throw std::runtime_error(dir + ": no *.sv RTL sources");
  // Yosys resolves the hierarchy after reading every file, so the order only has to be fixed
  // (for the cache key), not dependency order; except that a package must be read before a file
  // that names it in a parameter declaration (the units' SPEC_PARAMS width is shade_pkg's).
  const auto is_package = [](const fs::path& f) {
    const std::string n = f.filename().string();
    return n.size() > 7 && n.compare(n.size() - 7, 7, "_pkg.sv") == 0;
  };
  std::sort(files.begin(), files.end(), [&](const fs::path& a, const fs::path& b) {
    if (is_package(a) != is_package(b)) return is_package(a);
    return a < b;
  });
  return files;
}

namespace {

// The last 800 characters of a failed tool's log, for the error message.
std::string log_tail(const fs::path& log) {
  try {
    const std::string text = read_text_file(log.string());
    const auto from = text.size() > 800 ? text.size() - 800 : 0;
    return text.substr(from);
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace

void run_tool(const std::vector<std::string>& argv, const fs::path& log, const std::string& label,
              std::ostream* progress) {
  const auto t0 = std::chrono::steady_clock::now();
  auto job = std::async(std::launch::async, [&] { return run_process(argv, log.string()); });
  // On a terminal one line updated in place every second; in a log a line every 30 s.
  const bool terminal = progress == &std::cerr && ::isatty(STDERR_FILENO);
  int ticks = 0;
  while (job.wait_for(std::chrono::seconds(1)) != std::future_status::ready) {
    ++ticks;
    if (progress && (terminal || ticks % 30 == 0)) {
      const auto s =
          std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - t0);
      *progress << (terminal ? "\r" : "") << "[area] " << label << " ... " << s.count() << " s"
                << (terminal ? " " : "\n") << std::flush;
    }
  }
  const ProcessResult r = job.get();
  if (progress) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    *progress << (terminal ? "\r" : "") << "[area] " << label << " done in " << std::fixed
              << std::setprecision(1) << s << " s\n"
              << std::flush;
  }
  if (r.exit_code != 0) {
    const std::string tail = log_tail(log);
    throw std::runtime_error(label + " failed (exit " + std::to_string(r.exit_code) + "); log " +
                             log.string() + (tail.empty() ? "" : ":\n..." + tail));
  }
}

std::string yosys_script(const std::vector<fs::path>& files, const std::string& chparam,
                         const std::string& flow, const fs::path& work) {
  std::string body = flow;
  for (size_t at; (at = body.find("@WORK@")) != std::string::npos;)
    body.replace(at, 6, work.string());
  std::string s = "read_verilog -sv";
  for (const auto& f : files) s += " " + f.string();
  s += "\n";
  if (!chparam.empty()) s += "chparam " + chparam + " shade_unit\n";
  return s + body;
}

fs::path make_work_folder(const std::string& cache_dir, const std::string& key) {
  const fs::path work_root = cache_dir.empty() ? fs::temp_directory_path() : fs::path(cache_dir);
  std::string tmpl = (work_root / ("work-" + key + "-XXXXXX")).string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error(tmpl + ": cannot create a work folder");
  return tmpl;
}

double children_cpu_seconds() {
  struct rusage u {};
  ::getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace shadesim::flow_tools
