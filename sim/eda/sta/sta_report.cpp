#include "sim/eda/sta/sta_report.h"

#include <regex>
#include <sstream>
#include <stdexcept>

namespace shadesim {
namespace {

// "                  0.177    0.325    0.325 ^ _2791_/Q (DFFSR)": slew, delay, time, edge, pin.
// A port row is "... ^ rst_ni (in)"; the clock's launch row "0.000 0.000 0.000 ^ _1_/CLK (DFF)".
const std::regex& sta_pin_row() {
  static const std::regex re(
      R"(^\s*(-?[0-9.]+)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+([v^])\s+(\S+)\s+\((\S+)\)\s*$)");
  return re;
}
// "    4    0.070                              u_decoder.u_payload.pay_rem_q[5] (net)"
const std::regex& sta_net_row() {
  static const std::regex re(R"(^\s*([0-9]+)\s+(-?[0-9.]+)\s+(\S+) \(net\)\s*$)");
  return re;
}

StaStage sta_stage_of(const std::smatch& m) {
  StaStage s;
  s.slew_ns = std::stod(m[1].str());
  s.delay_ns = std::stod(m[2].str());
  s.time_ns = std::stod(m[3].str());
  s.edge = m[4].str()[0];
  const std::string where = m[5].str();
  s.cell = m[6].str();
  const auto slash = where.rfind('/');
  if (slash == std::string::npos || s.cell == "in" || s.cell == "out") {
    s.instance = where;  // a port
  } else {
    s.instance = where.substr(0, slash);
    s.pin = where.substr(slash + 1);
  }
  return s;
}

// The value at the front of a "   -0.095    3.905   library setup time" row.
double sta_leading_number(const std::string& line) { return std::stod(line); }

// One path's rows, from its "Startpoint:" line to its slack line.
class StaPathReader {
 public:
  explicit StaPathReader(StaPath& p) : p_(p) {}

  // Returns true on the slack line, which ends the path.
  bool line(const std::string& l) {
    static const std::regex start(R"(^Startpoint: (\S+) \((.*)\)\s*$)");
    static const std::regex end(R"(^Endpoint: (\S+) \((.*)\)\s*$)");
    static const std::regex group(R"(^Path Group: (\S+))");
    std::smatch m;
    if (std::regex_search(l, m, end)) {
      p_.endpoint = m[1];
      p_.end_kind = m[2];
    } else if (std::regex_search(l, m, group)) {
      p_.group = m[1];
    } else if (l.find("data arrival time") != std::string::npos) {
      if (!arrived_) p_.arrival_ns = last_time(l);
      arrived_ = true;
    } else if (l.find("library setup time") != std::string::npos ||
               l.find("library recovery time") != std::string::npos ||
               l.find("output external delay") != std::string::npos) {
      if (arrived_) p_.setup_ns = -sta_leading_number(l);
    } else if (l.find("data required time") != std::string::npos) {
      p_.required_ns = last_time(l);
    } else if (l.find("slack (") != std::string::npos) {
      p_.slack_ns = sta_leading_number(l);
      return true;
    } else if (!arrived_ && std::regex_match(l, m, sta_pin_row())) {
      p_.stages.push_back(sta_stage_of(m));
    } else if (!arrived_ && std::regex_match(l, m, sta_net_row()) && !p_.stages.empty()) {
      p_.stages.back().fanout = std::stoi(m[1].str());
      p_.stages.back().cap_pf = std::stod(m[2].str());
      p_.stages.back().net = m[3];
    } else if (std::regex_search(l, m, start)) {
      p_.startpoint = m[1];
      p_.start_kind = m[2];
    }
    return false;
  }

 private:
  static double last_time(const std::string& l) { return std::stod(l); }
  StaPath& p_;
  bool arrived_ = false;
};

}  // namespace

std::vector<StaPath> parse_sta_paths(const std::string& text, const std::string& source) {
  std::vector<StaPath> paths;
  std::istringstream is(text);
  std::optional<StaPathReader> reader;
  for (std::string l; std::getline(is, l);) {
    if (l.rfind("Startpoint: ", 0) == 0) {
      if (reader) throw std::runtime_error(source + ": a path without its slack line");
      paths.emplace_back();
      reader.emplace(paths.back());
    }
    if (reader && reader->line(l)) reader.reset();
  }
  if (reader) throw std::runtime_error(source + ": the last path has no slack line");
  if (paths.empty()) throw std::runtime_error(source + ": OpenSTA reported no path");
  for (const auto& p : paths) {
    if (p.stages.empty() || p.endpoint.empty())
      throw std::runtime_error(source + ": the path from " + p.startpoint + " has no rows");
  }
  return paths;
}

const StaPath& worst_path(const std::vector<StaPath>& paths) {
  if (paths.empty()) throw std::invalid_argument("worst_path: no paths");
  const StaPath* worst = &paths.front();
  for (const auto& p : paths)
    if (p.slack_ns < worst->slack_ns) worst = &p;
  return *worst;
}

std::optional<double> parse_worst_slack(const std::string& text) {
  static const std::regex re(R"((^|\n)worst slack (-?[0-9.]+))");
  std::smatch m;
  if (!std::regex_search(text, m, re)) return std::nullopt;
  return std::stod(m[2].str());
}

}  // namespace shadesim
