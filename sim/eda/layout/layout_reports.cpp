#include "sim/eda/layout/layout_reports.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace shadesim {
namespace {

std::vector<std::string> tokens_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  return t;
}

double number(const std::string& s, const std::string& source) {
  try {
    return std::stod(s);
  } catch (const std::exception&) {
    throw std::runtime_error(source + ": '" + s + "' is not a number");
  }
}

// One routed statement of a net ("+ ROUTED metal1 ( x y ) ( * y2 ) M2_M1" or "NEW ..."): its
// segments and vias into `d`. A '*' repeats the previous point's coordinate.
void read_route(const std::vector<std::string>& t, size_t at, const std::string& source,
                DefSummary& d) {
  if (at >= t.size()) return;
  const std::string& layer = t[at++];
  bool have = false;
  double px = 0, py = 0;
  while (at < t.size()) {
    if (t[at] == "(" && at + 3 < t.size()) {
      const double x = t[at + 1] == "*" ? px : number(t[at + 1], source) / d.units_per_micron;
      const double y = t[at + 2] == "*" ? py : number(t[at + 2], source) / d.units_per_micron;
      if (have && (x != px || y != py)) {
        d.segments.push_back({layer, px, py, x, y});
        const double len = std::abs(x - px) + std::abs(y - py);
        d.wire_length_um += len;
        d.wire_length_by_layer_um[layer] += len;
      }
      px = x, py = y, have = true;
      at += 3;  // past "( x y"; then an optional extension value and ")"
      while (at < t.size() && t[at] != ")") ++at;
      ++at;
    } else if (t[at] == ";" || t[at] == "NEW" || t[at] == "+") {
      return;
    } else {
      ++d.vias;  // a via name after a point
      ++at;
    }
  }
}

}  // namespace

std::map<std::string, LefSize> parse_lef_sizes(const std::string& text) {
  std::map<std::string, LefSize> sizes;
  std::istringstream in(text);
  std::string macro;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> t = tokens_of(line);
    if (t.size() >= 2 && t[0] == "MACRO") macro = t[1];
    if (t.size() >= 4 && t[0] == "SIZE" && t[2] == "BY" && !macro.empty()) {
      sizes[macro] = {std::stod(t[1]), std::stod(t[3])};
    }
    if (t.size() >= 2 && t[0] == "END" && t[1] == macro) macro.clear();
  }
  return sizes;
}

DefSummary parse_def(const std::string& text, const std::string& source,
                     const std::map<std::string, LefSize>& sizes, const std::string& fill_cell) {
  DefSummary d;
  std::istringstream in(text);
  std::string section;
  bool die = false;
  double cx0 = std::numeric_limits<double>::max(), cy0 = cx0, cx1 = -cx0, cy1 = -cx0;
  for (std::string line; std::getline(in, line);) {
    const std::vector<std::string> t = tokens_of(line);
    if (t.empty()) continue;
    if (t[0] == "UNITS" && t.size() >= 4) d.units_per_micron = number(t[3], source);
    if (t[0] == "DIEAREA" && t.size() >= 9 && d.units_per_micron > 0) {
      const double u = d.units_per_micron;
      d.die_x0_um = number(t[2], source) / u, d.die_y0_um = number(t[3], source) / u;
      d.die_x1_um = number(t[6], source) / u, d.die_y1_um = number(t[7], source) / u;
      die = true;
    }
    if (t[0] == "END" && t.size() >= 2 && t[1] == section) {
      section.clear();
      continue;
    }
    if (t[0] == "COMPONENTS" || t[0] == "PINS" || t[0] == "NETS" || t[0] == "SPECIALNETS") {
      section = t[0];
      continue;
    }
    if (section == "COMPONENTS" && t[0] == "-" && t.size() >= 3) {
      DefComponent c{t[1], t[2]};
      const auto placed = std::find(t.begin(), t.end(), "PLACED");
      const auto fixed = std::find(t.begin(), t.end(), "FIXED");
      const auto at = placed != t.end() ? placed : fixed;
      if (at != t.end() && std::distance(at, t.end()) >= 6) {
        c.x_um = number(*(at + 2), source) / d.units_per_micron;
        c.y_um = number(*(at + 3), source) / d.units_per_micron;
        c.orient = (at + 5)->front();
        c.flipped = c.orient == 'F';
        const auto s = sizes.find(c.cell);
        const double w = s == sizes.end() ? 0 : s->second.width_um;
        const double h = s == sizes.end() ? 0 : s->second.height_um;
        cx0 = std::min(cx0, c.x_um), cy0 = std::min(cy0, c.y_um);
        cx1 = std::max(cx1, c.x_um + w), cy1 = std::max(cy1, c.y_um + h);
      }
      ++d.components;
      if (c.cell == fill_cell) ++d.fill_cells;
      d.placed.push_back(c);
    } else if (section == "PINS" && t[0] == "-") {
      ++d.pins;
    } else if (section == "NETS") {
      if (t[0] == "-") ++d.nets;
      for (size_t i = 0; i < t.size(); ++i) {
        if ((t[i] == "ROUTED" && i > 0 && t[i - 1] == "+") || t[i] == "NEW") {
          read_route(t, i + 1, source, d);
          break;
        }
      }
    }
  }
  if (d.units_per_micron <= 0) throw std::runtime_error(source + ": no UNITS DISTANCE MICRONS");
  if (!die) throw std::runtime_error(source + ": no DIEAREA");
  if (cx1 >= cx0) d.core_x0_um = cx0, d.core_y0_um = cy0, d.core_x1_um = cx1, d.core_y1_um = cy1;
  return d;
}

int64_t parse_magic_drc_count(const std::string& log) {
  std::smatch m;
  if (std::regex_search(log, m, std::regex(R"(drc = (\d+))"))) return std::stoll(m[1]);
  if (log.find("No DRC errors found") != std::string::npos) return 0;
  return -1;
}

LvsResult parse_netgen_lvs(const std::string& log) {
  LvsResult r;
  std::smatch m;
  // The last verdict wins: netgen compares subcircuits first, the top cell last.
  const std::regex verdict(R"((Circuits match uniquely\.|Netlists do not match\.|)"
                           R"(Circuits match correctly\.|Netlists match uniquely\.))");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), verdict);
       it != std::sregex_iterator(); ++it) {
    r.found = true;
    r.verdict = (*it)[1];
  }
  if (std::regex_search(log, m, std::regex(R"(Total errors = (\d+))")))
    r.total_errors = std::stoll(m[1]);
  // Clean: a verdict, no mismatch anywhere (a subcircuit's counts), no error counted.
  r.clean = r.found && log.find("do not match") == std::string::npos && r.total_errors <= 0;
  return r;
}

}  // namespace shadesim
