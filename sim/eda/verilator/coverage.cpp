#include "sim/eda/verilator/coverage.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sim/eda/common/process.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// One point of a .dat line: C '<\001key\002value...>' count.
struct RawPoint {
  std::map<std::string, std::string> fields;
  long long count = 0;
};

RawPoint parse_point(const std::string& line, const std::string& where) {
  const auto open = line.find('\'');
  const auto close = line.rfind('\'');
  if (line.rfind("C ", 0) != 0 || open == std::string::npos || close <= open) {
    throw std::runtime_error(where + ": expected C '<point>' <count>");
  }
  RawPoint p;
  try {
    size_t used = 0;
    const std::string n = line.substr(close + 1);
    p.count = std::stoll(n, &used);
  } catch (const std::logic_error&) {
    throw std::runtime_error(where + ": the count after the point is not a number");
  }
  const std::string key = line.substr(open + 1, close - open - 1);
  size_t i = 0;
  while (i < key.size()) {
    if (key[i] != '\001') throw std::runtime_error(where + ": a field does not start with \\001");
    const auto sep = key.find('\002', i);
    const auto next = key.find('\001', i + 1);
    if (sep == std::string::npos || (next != std::string::npos && sep > next)) {
      throw std::runtime_error(where + ": a field has no \\002 between its name and value");
    }
    p.fields[key.substr(i + 1, sep - i - 1)] =
        key.substr(sep + 1, (next == std::string::npos ? key.size() : next) - sep - 1);
    i = next == std::string::npos ? key.size() : next;
  }
  return p;
}

// "3-5,8" -> {3, 4, 5, 8}
std::vector<int> line_list(const std::string& s, int fallback) {
  std::vector<int> out;
  std::stringstream ss(s);
  for (std::string part; std::getline(ss, part, ',');) {
    if (part.empty()) continue;
    const auto dash = part.find('-');
    try {
      const int a = std::stoi(part.substr(0, dash));
      const int b = dash == std::string::npos ? a : std::stoi(part.substr(dash + 1));
      for (int l = a; l <= b; ++l) out.push_back(l);
    } catch (const std::logic_error&) {
      // not a line list: fall back to the point's own line
    }
  }
  if (out.empty()) out.push_back(fallback);
  return out;
}

struct UnelaboratedSource {
  bool is_package = false;
  int code_lines = 0;  // non-blank lines from `module` to `endmodule` that are not only comments
};

// An rtl/ file no run elaborated: a package, or a module whose code lines count as uncovered.
UnelaboratedSource read_unelaborated(const std::string& path) {
  std::ifstream is(path);
  if (!is) throw std::runtime_error("coverage: cannot read " + path + " (an rtl/files.f source)");
  UnelaboratedSource out;
  bool in_module = false;
  for (std::string line; std::getline(is, line);) {
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line.compare(first, 2, "//") == 0) continue;
    const std::string code = line.substr(first);
    if (!in_module && code.rfind("package", 0) == 0) out.is_package = true;
    if (code.rfind("module", 0) == 0) in_module = true;
    if (in_module) ++out.code_lines;
    if (code.rfind("endmodule", 0) == 0) in_module = false;
  }
  if (out.code_lines > 0) out.is_package = false;
  return out;
}

bool under(const std::string& file, const std::string& dir) {
  const std::string d = fs::path(dir).lexically_normal().string();
  const std::string f = fs::path(file).lexically_normal().string();
  return f.size() > d.size() && f.compare(0, d.size(), d) == 0 &&
         (f[d.size()] == '/' || d.back() == '/');
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

void run_tool(const std::vector<std::string>& args, const std::string& what) {
  const ProcessResult r = run_process(args, "");
  if (r.exit_code != 0) {
    throw std::runtime_error("coverage: " + what + " failed (exit " + std::to_string(r.exit_code) +
                             "): " + r.output);
  }
}

}  // namespace

CoverageSummary summarize_coverage(const std::string& dat_path, const std::string& rtl_dir,
                                   const std::vector<std::string>& rtl_files) {
  std::ifstream is(dat_path);
  if (!is) throw std::runtime_error("coverage: cannot read " + dat_path);
  // Per file: line -> whether a point naming it counted; toggles.
  struct Acc {
    std::map<int, bool> lines;
    int toggles = 0, toggles_hit = 0;
  };
  std::map<std::string, Acc> acc;
  std::map<std::string, CoverPoint> user;
  std::string line;
  int n = 0;
  while (std::getline(is, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    const RawPoint p = parse_point(line, dat_path + ":" + std::to_string(n));
    const std::string file = p.fields.count("f") ? p.fields.at("f") : "";
    const std::string page = p.fields.count("page") ? p.fields.at("page") : "";
    int lineno = 0;
    try {
      lineno = p.fields.count("l") ? std::stoi(p.fields.at("l")) : 0;
    } catch (const std::logic_error&) {
      throw std::runtime_error(dat_path + ":" + std::to_string(n) +
                               ": the line field is not a number");
    }
    const std::string type = page.substr(0, page.find('/'));
    if (type == "v_line" || type == "v_branch") {
      for (int l : line_list(p.fields.count("S") ? p.fields.at("S") : "", lineno)) {
        acc[file].lines[l] = acc[file].lines[l] || p.count > 0;
      }
    } else if (type == "v_toggle") {
      ++acc[file].toggles;
      if (p.count > 0) ++acc[file].toggles_hit;
    } else if (type == "v_user") {
      const std::string name = p.fields.count("o") ? p.fields.at("o") : "?";
      // Named by the cover property's label; instances of one module merge into one point.
      const std::string key = name + "@" + file + ":" + std::to_string(lineno);
      CoverPoint& u = user[key];
      u.name = name;
      u.file = file;
      u.line = lineno;
      u.count += p.count;
    }
  }
  CoverageSummary s;
  for (const auto& [file, a] : acc) {
    CoverageFile f;
    f.path = file;
    for (const auto& [l, hit] : a.lines) {
      ++f.lines;
      if (hit)
        ++f.lines_hit;
      else
        f.uncovered_lines.push_back(l);
    }
    f.toggles = a.toggles;
    f.toggles_hit = a.toggles_hit;
    if (under(file, rtl_dir)) {
      s.lines += f.lines;
      s.lines_hit += f.lines_hit;
      s.toggles += f.toggles;
      s.toggles_hit += f.toggles_hit;
    }
    s.files.push_back(f);
  }
  for (const auto& [key, u] : user) s.user.push_back(u);
  std::sort(s.user.begin(), s.user.end(), [](const CoverPoint& a, const CoverPoint& b) {
    return a.name != b.name ? a.name < b.name : a.line < b.line;
  });
  for (const auto& f : rtl_files) {
    const std::string norm = fs::path(f).lexically_normal().string();
    const bool seen = std::any_of(s.files.begin(), s.files.end(), [&](const CoverageFile& c) {
      return fs::path(c.path).lexically_normal().string() == norm;
    });
    if (seen) continue;
    const UnelaboratedSource src = read_unelaborated(f);
    if (src.is_package) {
      s.packages.push_back(f);
      continue;
    }
    s.files_without_points.push_back(f);
    CoverageFile row;
    row.path = f;
    row.lines = src.code_lines;
    row.elaborated = false;
    if (under(f, rtl_dir)) s.lines += row.lines;
    s.files.push_back(row);
  }
  std::sort(s.files.begin(), s.files.end(),
            [](const CoverageFile& a, const CoverageFile& b) { return a.path < b.path; });
  return s;
}

std::vector<CoverageExclusion> list_exclusions(const std::vector<std::string>& files) {
  std::vector<CoverageExclusion> out;
  for (const auto& file : files) {
    std::ifstream is(file);
    if (!is) throw std::runtime_error("coverage: cannot read " + file);
    std::string line;
    int n = 0;
    bool open = false;
    CoverageExclusion cur;
    while (std::getline(is, line)) {
      ++n;
      const bool off = line.find("verilator coverage_off") != std::string::npos;
      const bool on = line.find("verilator coverage_on") != std::string::npos;
      if (off) {
        if (open)
          throw std::runtime_error(file + ":" + std::to_string(n) +
                                   ": coverage_off inside the region opened on line " +
                                   std::to_string(cur.first_line));
        // The reason: the line comment after the pragma.
        const auto end = line.find("*/");
        const auto slash =
            line.find("//", end == std::string::npos ? line.find("coverage_off") : end);
        const std::string reason = slash == std::string::npos ? "" : trim(line.substr(slash + 2));
        if (reason.empty()) {
          throw std::runtime_error(
              file + ":" + std::to_string(n) +
              ": a coverage_off without a reason; write /* verilator coverage_off */ // why");
        }
        cur = CoverageExclusion{file, n, n, reason};
        open = true;
      } else if (on) {
        if (!open)
          throw std::runtime_error(file + ":" + std::to_string(n) +
                                   ": coverage_on with no coverage_off before it");
        cur.last_line = n;
        out.push_back(cur);
        open = false;
      }
    }
    if (open)
      throw std::runtime_error(file + ":" + std::to_string(cur.first_line) +
                               ": coverage_off is never switched back on");
  }
  return out;
}

void merge_coverage(const std::vector<std::string>& inputs, const std::string& merged,
                    const std::string& info, const std::string& annotate_dir) {
  if (inputs.empty()) throw std::runtime_error("coverage: no run wrote a coverage file");
  std::vector<std::string> args = {"verilator_coverage", "--write", merged};
  args.insert(args.end(), inputs.begin(), inputs.end());
  args[0] = find_program("verilator_coverage", "verilator", "coverage");
  run_tool(args, "verilator_coverage --write " + merged);
  run_tool({args[0], "--write-info", info, merged}, "verilator_coverage --write-info " + info);
  fs::remove_all(annotate_dir);
  // --annotate-min 1: a line is marked uncovered (%000000) only when nothing counted there.
  run_tool({args[0], "--annotate", annotate_dir, "--annotate-min", "1", merged},
           "verilator_coverage --annotate " + annotate_dir);
}

}  // namespace shadesim
