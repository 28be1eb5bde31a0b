// Reading OpenSTA's reports (2019 snapshot, Debian's opensta): the paths of `report_checks
// -path_delay max -fields {capacitance slew net} -digits N` and the line of `report_worst_slack`.
//
// A path is a Startpoint / Endpoint header, then rows "slew delay time edge pin (cell)" for each
// pin (with -fields net, each followed by a "fanout cap name (net)" row), the data arrival time,
// the clock's required time with its "library setup time" (or "output external delay") row, and
// the slack.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace shadesim {

// One cell output (or port) on a path, with the net it drives.
struct StaStage {
  std::string instance;  // "_2791_", "fanbuf_22"; a port's name for a port row
  std::string pin;       // "Q", "Y"; "" for a port
  std::string cell;      // "DFFSR"; "in" / "out" for a port
  char edge = '^';       // '^' rising, 'v' falling
  double delay_ns = 0, time_ns = 0, slew_ns = 0;
  std::string net;  // the net it drives ("" on the endpoint's row)
  int fanout = -1;  // of that net; -1 when not reported
  double cap_pf = 0;
};

struct StaPath {
  std::string startpoint, endpoint;  // instance or port names
  std::string start_kind, end_kind;  // the header's parenthesis ("rising edge-triggered ...")
  std::string group;                 // "clk", "**async_default**"
  std::vector<StaStage> stages;      // the launch clock pin first, the endpoint's pin last
  double arrival_ns = 0, required_ns = 0, slack_ns = 0;
  // What the endpoint takes off the period: the library setup (or recovery) time, or the output
  // external delay; positive.
  double setup_ns = 0;
};

// Every path in a report_checks output, in order. Throws std::runtime_error naming `source` when
// the text holds no path or a path is cut short.
std::vector<StaPath> parse_sta_paths(const std::string& text, const std::string& source);

// The path with the least slack (the first of equals).
const StaPath& worst_path(const std::vector<StaPath>& paths);

// report_worst_slack's "worst slack X"; nullopt when the text has none.
std::optional<double> parse_worst_slack(const std::string& text);

}  // namespace shadesim
