// OpenSTA under the flow's constraints (sim/eda/sta/sta_constraints.h) against timing worked out
// here from the osu018 liberty's own NLDM tables: a hand-built netlist (a flip-flop, two
// inverters, a flip-flop, and the ports) whose three paths - input port to a D, flip-flop to
// flip-flop, flip-flop to output port - this test times by reading the .lib's cell_rise /
// cell_fall / *_transition / setup tables itself and interpolating them bilinearly (linearly
// beyond their ends, as NLDM is), with the clock's uncertainty, the input's driving buffer and
// delay and the output's load and delay added by hand. A constraint left out of the Tcl, a
// wrong load or a wrong uncertainty moves a slack by more than the tolerance. Also the guard
// band's arithmetic and the constraints' JSON. Needs sta (opensta) and qflow-tech-osu018; about
// a second.
#include "sim/eda/sta/sta_constraints.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "sim/eda/sta/liberty.h"
#include "sim/eda/sta/liberty_flow.h"
#include "sim/eda/sta/sta_report.h"
#include "tests/support/cli_run.h"
#include "tests/support/eda_tools.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream is(p);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

// ---- a small reader of the liberty's NLDM tables, independent of sim/eda/sta/liberty.cpp --------

// The text of the group starting at `open` (the index of its '{'), braces matched.
std::string group_body(const std::string& text, size_t open) {
  int depth = 0;
  for (size_t i = open; i < text.size(); ++i) {
    if (text[i] == '{') ++depth;
    if (text[i] == '}' && --depth == 0) return text.substr(open + 1, i - open - 1);
  }
  throw std::runtime_error("unbalanced group");
}

// The body of the first group `head` (e.g. "cell (INVX1)") in `text`.
std::string find_group(const std::string& text, const std::string& head) {
  const size_t at = text.find(head);
  if (at == std::string::npos) throw std::runtime_error("no " + head);
  return group_body(text, text.find('{', at));
}

std::vector<double> numbers(const std::string& s) {
  std::vector<double> out;
  static const std::regex number(R"(-?[0-9]+(\.[0-9]*)?(e-?[0-9]+)?)");
  for (std::sregex_iterator it(s.begin(), s.end(), number), end; it != end; ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

struct Table {
  std::vector<double> index1, index2, values;  // values row-major: index1 rows
};

Table parse_table(const std::string& body) {
  Table t;
  std::smatch m;
  std::regex_search(body, m, std::regex(R"(index_1\s*\(\s*\"([^\"]*)\")"));
  t.index1 = numbers(m[1].str());
  if (std::regex_search(body, m, std::regex(R"(index_2\s*\(\s*\"([^\"]*)\")")))
    t.index2 = numbers(m[1].str());
  const size_t v = body.find("values");
  t.values = numbers(body.substr(body.find('(', v), body.find(')', v) - body.find('(', v)));
  return t;
}

// Linear interpolation weight of x between the two index points around it (or the end pair).
std::pair<size_t, double> segment(const std::vector<double>& index, double x) {
  size_t i = 0;
  while (i + 2 < index.size() && x > index[i + 1]) ++i;
  return {i, (x - index[i]) / (index[i + 1] - index[i])};
}

double lookup(const Table& t, double x1, double x2) {
  const auto [i, f] = segment(t.index1, x1);
  if (t.index2.empty()) return t.values[i] + f * (t.values[i + 1] - t.values[i]);
  const size_t n = t.index2.size();
  const auto [j, g] = segment(t.index2, x2);
  const auto at = [&](size_t a, size_t b) { return t.values[a * n + b]; };
  const double lo = at(i, j) + g * (at(i, j + 1) - at(i, j));
  const double hi = at(i + 1, j) + g * (at(i + 1, j + 1) - at(i + 1, j));
  return lo + f * (hi - lo);
}

// A table of pin `pin` of `cell` in the timing group related to `related` (and of
// `timing_type` when given).
Table pin_table(const std::string& lib, const std::string& cell, const std::string& pin,
                const std::string& related, const std::string& timing_type,
                const std::string& table) {
  const std::string c = find_group(lib, "cell (" + cell + ")");
  const std::string p = find_group(c, "pin(" + pin + ")");
  for (size_t at = p.find("timing()"); at != std::string::npos; at = p.find("timing()", at + 1)) {
    const std::string t = group_body(p, p.find('{', at));
    if (t.find("related_pin : \"" + related + "\"") == std::string::npos) continue;
    if (!timing_type.empty() && t.find("timing_type : " + timing_type) == std::string::npos)
      continue;
    const size_t h = t.find(table + "(");
    if (h == std::string::npos) continue;
    return parse_table(group_body(t, t.find('{', h)));
  }
  throw std::runtime_error(cell + "/" + pin + ": no " + table + " related to " + related);
}

double pin_cap(const std::string& lib, const std::string& cell, const std::string& pin, bool rise) {
  const std::string p = find_group(find_group(lib, "cell (" + cell + ")"), "pin(" + pin + ")");
  std::smatch m;
  std::regex_search(
      p, m, std::regex(std::string(rise ? "rise" : "fall") + R"(_capacitance : ([0-9.e-]+))"));
  return std::stod(m[1].str());
}

// A timing arc's delay and output slew: cell_rise/rise_transition for a rising output.
struct Edge {
  double time = 0, slew = 0;
};
Edge arc(const std::string& lib, const std::string& cell, const std::string& out,
         const std::string& in, bool out_rise, double load, double in_slew, double start) {
  const std::string d = out_rise ? "cell_rise" : "cell_fall";
  const std::string s = out_rise ? "rise_transition" : "fall_transition";
  return {start + lookup(pin_table(lib, cell, out, in, "", d), load, in_slew),
          lookup(pin_table(lib, cell, out, in, "", s), load, in_slew)};
}
double setup(const std::string& lib, bool d_rise, double clock_slew, double d_slew) {
  return lookup(pin_table(lib, "DFFPOSX1", "D", "CLK", "setup_rising",
                          d_rise ? "rise_constraint" : "fall_constraint"),
                clock_slew, d_slew);
}

const char* kNetlist = R"(module shade_unit (clk_i, d_i, q_o);
  input clk_i;
  input d_i;
  output q_o;
  wire n1, n2, n3;
  DFFPOSX1 a (.CLK(clk_i), .D(d_i), .Q(n1));
  INVX1 u1 (.A(n1), .Y(n2));
  INVX1 u2 (.A(n2), .Y(n3));
  DFFPOSX1 b (.CLK(clk_i), .D(n3), .Q(q_o));
endmodule
)";

TEST(StaConstraints, OpenStaMatchesTheLibertyTablesWorkedByHand) {
  SHADESIM_NEEDS_TOOLS(
      run_shell("command -v sta").status == 0 && fs::exists(kDefaultLiberty),
      "sta or " << kDefaultLiberty << " (Debian packages opensta, qflow-tech-osu018)");
  const fs::path dir = temp_dir("sta_constraints", "nldm");
  std::ofstream(dir / "n.v") << kNetlist;
  const std::string lib = read(kDefaultLiberty);
  const LibertyLibrary library = read_liberty(kDefaultLiberty);
  // Input delay and output delay chosen here (the flow measures them on DFFPOSX1).
  const double in_delay = 0.5, out_delay = 1.5, period = 4.0;
  StaConstraints policy;
  const ResolvedConstraints c = resolve_constraints(policy, library, in_delay, out_delay);
  ASSERT_EQ(c.driving_cell, "BUFX2");
  ASSERT_EQ(c.load_cell, "DFFPOSX1");
  const double unc = policy.clock_uncertainty_ns;
  ASSERT_GT(unc, 0);

  const std::string tcl =
      sta_setup_tcl(kDefaultLiberty, (dir / "n.v").string(), period, c) +
      "report_checks -path_delay max -fields {capacitance slew net} -digits 4 -to b/D\n"
      "report_checks -path_delay max -fields {capacitance slew net} -digits 4 -to q_o\n"
      "report_checks -path_delay max -fields {capacitance slew net} -digits 4 -from d_i\n";
  std::ofstream(dir / "t.tcl") << tcl;
  const Result sta = run_shell("sta -no_splash -exit " + (dir / "t.tcl").string());
  ASSERT_EQ(sta.status, 0) << sta.output;
  ASSERT_EQ(sta.output.find("Error"), std::string::npos) << sta.output;
  const std::vector<StaPath> paths = parse_sta_paths(sta.output, "t.tcl");
  ASSERT_EQ(paths.size(), 3u) << sta.output;

  // The ideal clock's slew is 0: the tables' first segment extended, as NLDM is.
  const double clock_slew = 0;
  double reg_slack = 1e9, out_slack = 1e9, in_slack = 1e9;
  for (const bool q_rise : {true, false}) {
    // a/Q into u1/A, u1/Y into u2/A (the opposite edge), u2/Y into b/D (a/Q's edge again).
    const Edge q =
        arc(lib, "DFFPOSX1", "Q", "CLK", q_rise, pin_cap(lib, "INVX1", "A", q_rise), clock_slew, 0);
    const Edge y1 =
        arc(lib, "INVX1", "Y", "A", !q_rise, pin_cap(lib, "INVX1", "A", !q_rise), q.slew, q.time);
    const Edge y2 = arc(lib, "INVX1", "Y", "A", q_rise, pin_cap(lib, "DFFPOSX1", "D", q_rise),
                        y1.slew, y1.time);
    reg_slack =
        std::min(reg_slack, period - unc - setup(lib, q_rise, clock_slew, y2.slew) - y2.time);
    // b/Q into the port's load: 4 DFFPOSX1 D pins (set_load: one figure for both edges).
    const double load = 4 * library.cell("DFFPOSX1").pin("D")->capacitance;
    const Edge o = arc(lib, "DFFPOSX1", "Q", "CLK", q_rise, load, clock_slew, 0);
    out_slack = std::min(out_slack, period - unc - out_delay - o.time);
    // d_i: the input delay, then BUFX2 (its input ideal) into a/D. SDC's driving cell adds only
    // the load's share of the cell's delay (its delay at the load less its delay unloaded: the
    // input delay already holds the launch) and the cell's slew at the load.
    const Edge i =
        arc(lib, "BUFX2", "Y", "A", q_rise, pin_cap(lib, "DFFPOSX1", "D", q_rise), 0, in_delay);
    const Edge unloaded = arc(lib, "BUFX2", "Y", "A", q_rise, 0, 0, 0);
    in_slack = std::min(
        in_slack, period - unc - setup(lib, q_rise, clock_slew, i.slew) - (i.time - unloaded.time));
  }
  EXPECT_NEAR(paths[0].slack_ns, reg_slack, 0.002) << sta.output;
  EXPECT_NEAR(paths[1].slack_ns, out_slack, 0.002) << sta.output;
  EXPECT_NEAR(paths[2].slack_ns, in_slack, 0.002) << sta.output;
  // The flow's Fmax on this netlist: 1000 / (period - the worst of the three).
  const double worst = std::min({reg_slack, out_slack, in_slack});
  EXPECT_NEAR(1000.0 / (period - worst_path(paths).slack_ns), 1000.0 / (period - worst), 0.1);
  fs::remove_all(dir);
}

TEST(StaConstraints, TheGuardBandAndTheJson) {
  StaConstraints p;
  p.guard_band = 0.05;
  EXPECT_NEAR(required_fmax_mhz(250, p), 263.158, 0.001);  // 250 / 0.95
  p.guard_band = 0.2;
  EXPECT_NEAR(required_fmax_mhz(100, p), 125.0, 1e-9);
  if (!fs::exists(kDefaultLiberty)) GTEST_SKIP() << kDefaultLiberty << " absent";
  const LibertyLibrary lib = read_liberty(kDefaultLiberty);
  const ResolvedConstraints c = resolve_constraints(StaConstraints{}, lib, 0.3, 0.1);
  // 4 x DFFPOSX1's D capacitance, read off the .lib text by eye: 0.00882947 pF.
  EXPECT_NEAR(c.output_load_pf, 4 * 0.00882947, 1e-9);
  EXPECT_EQ(c.driving_pin, "Y");
  const ResolvedConstraints back = constraints_from_json(constraints_to_json(c), "test");
  EXPECT_EQ(back.driving_cell, c.driving_cell);
  EXPECT_EQ(back.output_load_pf, c.output_load_pf);
  EXPECT_EQ(back.policy.guard_band, c.policy.guard_band);
  EXPECT_THROW(constraints_from_json(nlohmann::json::object(), "x.json"), std::runtime_error);
}

}  // namespace
}  // namespace shadesim
