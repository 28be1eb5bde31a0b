#include "sim/engines/explore_csv.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <sstream>

#include "model/text_file.h"
#include "sim/engines/explore_front.h"

namespace shadesim {
namespace {

// A CSV field in double quotes, inner quotes doubled (RFC 4180).
std::string csv_quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// (Named apart from explore.cpp's over_1lsb_pct: the two can share a unity file.)
double csv_over_1lsb_pct(const ErrorStats& e) {
  return e.pixels ? 100.0 * static_cast<double>(e.pixels_over_1lsb) / static_cast<double>(e.pixels)
                  : 0.0;
}

// ",value" or "," where there is none: a column a spreadsheet reads as empty, not as 0.
void optional_field(std::ostream& os, const std::optional<double>& v) {
  os << ',';
  if (v) os << fmt::format("{}", *v);  // shortest exact: um^2 run to six digits and more
}

// The library columns of one point (empty unless measured).
void library_fields(std::ostream& os, const ExplorePoint& p, const ExploreJobOptions& o) {
  const MeasuredArea* m = p.measured ? &*p.measured : nullptr;
  optional_field(os, m ? m->library_area_um2 : std::nullopt);
  optional_field(os, m ? m->library_fmax_mhz : std::nullopt);
  optional_field(os, p.library_mpixel_per_s());
  const std::optional<bool> meets = meets_clock(p, o);
  os << ',';
  if (meets) os << (*meets ? 1 : 0);
}

}  // namespace

void write_explore_csv(const std::string& path, const ExploreResult& r, int channels,
                       const ExploreJobOptions& o) {
  std::ostringstream os;
  os << "index,phase,stage,knob,value,valid,config,max_code_lsb";
  for (int c = 0; c < channels; ++c) os << ",max_code_lsb_ch" << c;
  os << ",mean_code_lsb";
  for (int c = 0; c < channels; ++c) os << ",mean_code_lsb_ch" << c;
  os << ",psnr_db,max_real_lsb,pct_over_1lsb,cycles_per_pixel,area,meets_budget,pareto,chosen"
     << ",library_area_um2,library_fmax_mhz,library_mpixel_per_s,meets_clock\n";
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    const ExplorePoint& p = r.points[i];
    const ErrorStats& e = p.figures.error;
    os << i << ',' << csv_quote(p.phase) << ',' << csv_quote(p.stage) << ',' << csv_quote(p.knob)
       << ',' << csv_quote(p.value) << ',' << (p.valid ? 1 : 0) << ','
       << csv_quote(p.valid ? p.config.to_string() : p.invalid_reason);
    if (!p.valid) {
      os << std::string(static_cast<size_t>(2 * channels + 10), ',') << (r.chosen == i ? 1 : 0)
         << ",,,,\n";
      continue;
    }
    os << ',' << e.max_code_lsb;
    for (int c = 0; c < channels; ++c) os << ',' << e.max_code_lsb_channel[static_cast<size_t>(c)];
    os << ',' << e.mean_code_lsb;
    for (int c = 0; c < channels; ++c) os << ',' << e.mean_code_lsb_channel[static_cast<size_t>(c)];
    os << ',' << (std::isinf(e.psnr_db) ? std::string("inf") : std::to_string(e.psnr_db)) << ','
       << e.max_real_lsb << ',' << csv_over_1lsb_pct(e) << ',' << p.figures.cycles_per_pixel << ','
       << p.figures.area.cells << ',' << (p.meets_budget ? 1 : 0) << ',' << (p.pareto ? 1 : 0)
       << ',' << (r.chosen == i ? 1 : 0);
    library_fields(os, p, o);
    os << '\n';
  }
  write_text_file(path, os.str());
}

}  // namespace shadesim
