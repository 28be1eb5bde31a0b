#include "sim/report/report_page.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "sim/regress/junit.h"

namespace shadesim {
namespace fs = std::filesystem;

namespace {

using nlohmann::json;

std::string esc(const std::string& s) { return xml_escape(s); }

// A value of a report as table text: numbers to 4 significant digits, strings as they are.
std::string text(const json& v) {
  if (v.is_null()) return "-";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  if (v.is_number_float()) {
    const double d = v.get<double>();
    std::ostringstream os;
    if (std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 1e15) {
      os << static_cast<long long>(d);
    } else if (std::fabs(d) >= 1000 && std::fabs(d) < 1e15) {
      os << std::fixed << std::setprecision(1) << d;
    } else {
      os << std::setprecision(4) << d;  // 4 significant digits
    }
    return os.str();
  }
  if (v.is_array() &&
      std::none_of(v.begin(), v.end(), [](const json& e) { return e.is_structured(); })) {
    std::string joined;
    for (const auto& e : v) joined += (joined.empty() ? "" : ", ") + text(e);
    return joined.empty() ? "(none)" : joined;
  }
  return v.dump();
}

// doc[a][b]..., or null where a key is missing or a level is not an object.
json at(const json& doc, std::initializer_list<const char*> keys) {
  const json* p = &doc;
  for (const char* k : keys) {
    if (!p->is_object()) return nullptr;
    const auto it = p->find(k);
    if (it == p->end()) return nullptr;
    p = &*it;
  }
  return *p;
}

std::string cell(const json& v) { return "<td>" + esc(text(v)) + "</td>"; }

std::string base64(const std::string& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = static_cast<uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<uint8_t>(bytes[i + 2]);
    out += abc[(n >> 18) & 63];
    out += abc[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? abc[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? abc[n & 63] : '=';
  }
  return out;
}

// <img> with the PNG embedded, or a note naming the file when it cannot be read.
std::string image(const std::string& path, const std::string& alt) {
  std::ifstream is(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << is.rdbuf();
  if (!is || bytes.str().size() < 8 || bytes.str().compare(1, 3, "PNG") != 0) {
    return "<p class=\"missing\">" + esc(path) + ": not a readable PNG (" + esc(alt) + ")</p>";
  }
  return "<img src=\"data:image/png;base64," + base64(bytes.str()) + "\" alt=\"" + esc(alt) + "\">";
}

// An image a report names: as written (relative to where the command ran), else beside the report.
std::string locate(const std::string& named, const std::string& report_path) {
  if (named.empty() || fs::exists(named)) return named;
  const fs::path beside = fs::path(report_path).parent_path() / fs::path(named).filename();
  return fs::exists(beside) ? beside.string() : named;
}

std::string source(const ReportInput& in) {
  return "<p class=\"source\">from <code>" + esc(in.path) + "</code> (" + writer_of(in.kind) +
         ")</p>\n";
}

std::string none(ReportKind kind, const std::string& recipe) {
  return "<p class=\"missing\">No input: no " + std::string(writer_of(kind)) +
         " file was given or found. " + recipe + "</p>\n";
}

const ReportPlot* plot_of(const ReportPage& page, const std::string& path) {
  for (const auto& p : page.plots) {
    if (p.input_path == path) return &p;
  }
  return nullptr;
}

std::string plot(const ReportPage& page, const ReportInput& in, const std::string& alt) {
  const ReportPlot* p = plot_of(page, in.path);
  if (!p) return "<p class=\"missing\">no plot was drawn for " + esc(in.path) + "</p>\n";
  if (!p->error.empty())
    return "<p class=\"missing\">scripts/plot " + esc(in.path) + ": " + esc(p->error) + "</p>\n";
  return image(p->png_path, alt) + "\n";
}

// A table of the rows of an array of objects: the given columns, or every key the rows have.
// A JSON key as words for a heading: `cycles_per_pixel` -> "cycles per pixel", `stream.words`
// -> "stream: words".
std::string plain(const std::string& key) {
  std::string out;
  for (size_t i = 0; i < key.size(); ++i) {
    if (key[i] == '_') {
      out += ' ';
    } else if (key[i] == '.') {
      out += ": ";
    } else {
      out += key[i];
    }
  }
  return out;
}

std::string table(const json& rows, std::vector<std::pair<std::string, std::string>> columns,
                  size_t limit = 200) {
  if (!rows.is_array() || rows.empty()) return "<p class=\"missing\">(no rows)</p>\n";
  if (columns.empty()) {
    for (const auto& r : rows) {
      if (!r.is_object()) continue;
      for (const auto& [k, v] : r.items()) {
        bool seen = false;
        for (const auto& c : columns) seen = seen || c.first == k;
        if (!seen) columns.emplace_back(k, plain(k));
      }
    }
  }
  std::string h = "<table><tr>";
  for (const auto& c : columns) h += "<th>" + esc(c.second) + "</th>";
  h += "</tr>\n";
  size_t n = 0;
  for (const auto& r : rows) {
    if (n++ == limit) break;
    h += "<tr>";
    for (const auto& c : columns)
      h += cell(r.is_object() && r.contains(c.first) ? r[c.first] : json(nullptr));
    h += "</tr>\n";
  }
  h += "</table>\n";
  if (rows.size() > limit)
    h += "<p>(" + std::to_string(rows.size() - limit) + " more rows not shown)</p>\n";
  return h;
}

// Key/value rows of an object's scalars (nested objects flattened to a.b).
void flatten(const json& obj, const std::string& prefix,
             std::vector<std::pair<std::string, json>>& out) {
  for (const auto& [k, v] : obj.items()) {
    if (v.is_object()) {
      flatten(v, prefix + k + ".", out);
    } else if (!v.is_array() ||
               std::none_of(v.begin(), v.end(), [](const json& e) { return e.is_structured(); })) {
      out.emplace_back(prefix + k, v);
    }
  }
}

std::string key_values(const std::vector<std::pair<std::string, json>>& rows) {
  std::string h = "<table class=\"kv\">";
  for (const auto& [k, v] : rows) h += "<tr><th>" + esc(k) + "</th>" + cell(v) + "</tr>";
  return h + "</table>\n";
}

std::string scene_name(const json& doc) {
  const json s = at(doc, {"scene"});
  return s.is_string() ? fs::path(s.get<std::string>()).stem().string() : "(no scene name)";
}

// The heat map's colour scale (host/image.h error_heat_map): black exactly 0, then blue, green,
// yellow, red at full scale and beyond; dark grey where no pixel was shaded.
std::string heat_scale(const json& render) {
  const json full = at(render, {"heat_scale_lsb"});
  if (!full.is_number()) {
    return "<p class=\"missing\">colour scale: not recorded (render JSON without "
           "heat_scale_lsb)</p>\n";
  }
  const std::string f = text(full);
  return "<p class=\"scale\">error colour scale: <span class=\"swatch\" "
         "style=\"background:#000\"></span> 0 LSB <span class=\"bar\"></span> " +
         esc(f) + " LSB and more (blue at &gt; 0, green " +
         esc(text(json(full.get<double>() / 3))) + ", yellow " +
         esc(text(json(2 * full.get<double>() / 3))) + ", red " + esc(f) +
         ") <span class=\"swatch\" style=\"background:#303030\"></span> not shaded</p>\n";
}

std::string render_section(const ReportInput& in) {
  const json& d = in.doc;
  std::string h = "<h3>" + esc(scene_name(d)) + "</h3>\n" + source(in);
  const json compare = at(d, {"images", "compare"});
  h += compare.is_string()
           ? image(locate(compare.get<std::string>(), in.path),
                   scene_name(d) + ": model | reference | error")
           : "<p class=\"missing\">" + esc(in.path) +
                 ": no images.compare (expected the path of render's compare.png)</p>";
  h += "<p class=\"caption\">model | reference | error heat map</p>\n" + heat_scale(d);
  h += key_values(
      {{"image", json(text(at(d, {"width"})) + "x" + text(at(d, {"height"})))},
       {"specular unit", at(d, {"specular_unit"})},
       {"pixels", at(d, {"pixels"})},
       {"triangles (mesh / after setup)", json(text(at(d, {"triangles", "mesh"})) + " / " +
                                               text(at(d, {"triangles", "after_setup"})))},
       {"clipped at the near plane", at(d, {"triangles", "clipped_near"})},
       {"max error (LSB, codes)", at(d, {"error", "max_code_lsb"})},
       {"mean error (LSB)", at(d, {"error", "mean_code_lsb"})},
       {"PSNR (dB)", at(d, {"error", "psnr_db"})},
       {"max error before rounding (LSB)", at(d, {"error", "max_real_lsb"})},
       {"pixels more than 1 LSB off", at(d, {"error", "pixels_over_1lsb"})},
       {"stream words", at(d, {"stream", "words"})}});
  return h;
}

std::string render_units_section(const ReportInput& in) {
  return "<h3>" + esc(scene_name(in.doc)) + ": every specular unit</h3>\n" + source(in) +
         table(in.doc["units"], {{"unit", "unit"},
                                 {"configuration", "configuration"},
                                 {"max_code_lsb", "max LSB"},
                                 {"mean_code_lsb", "mean LSB"},
                                 {"psnr_db", "PSNR dB"},
                                 {"table_load_cycles", "table load cycles"}});
}

std::string spec_error_section(const ReportPage& page, const ReportInput& in) {
  const json ex = in.doc["exponents"];
  std::string range = ex.empty() ? "none"
                                 : text(ex.front()) + " .. " + text(ex.back()) + " (" +
                                       std::to_string(ex.size()) + " values)";
  return source(in) + "<p>exponents " + esc(range) + "</p>\n" +
         plot(page, in, "specular units: worst error against cost, Pareto front ringed") +
         table(in.doc["units"], {{"name", "unit"},
                                 {"config", "configuration"},
                                 {"epi_rel", "epicentre rel."},
                                 {"bloom_rel", "blooming rel."},
                                 {"abs_lsb", "max abs LSB"},
                                 {"n_within_1pct", "n within 1 %"},
                                 {"table_bits", "table bits"},
                                 {"multipliers", "multipliers"},
                                 {"cycles_per_pixel", "cycles/px"},
                                 {"latency", "latency"},
                                 {"area", "area proxy"},
                                 {"pareto", "Pareto"}});
}

std::string explore_section(const ReportPage& page, const ReportInput& in) {
  const json& d = in.doc;
  const json points = at(d, {"points"});
  auto point = [&](const json& index) -> json {
    if (!index.is_number_integer() || !points.is_array() || index.get<long>() < 0 ||
        index.get<size_t>() >= points.size()) {
      return nullptr;
    }
    return points[index.get<size_t>()];
  };
  json rows = json::array();
  for (const auto& [label, index] : {std::pair<const char*, json>{"start", at(d, {"start_index"})},
                                     {"chosen", at(d, {"chosen_index"})}}) {
    const json p = point(index);
    rows.push_back({{"point", label},
                    {"config", at(p, {"config_text"})},
                    {"max", at(p, {"error", "max_code_lsb"})},
                    {"mean", at(p, {"error", "mean_code_lsb"})},
                    {"area", at(p, {"area"})},
                    {"cpp", at(p, {"cycles_per_pixel"})}});
  }
  return source(in) +
         key_values({{"scenes", at(d, {"scenes"})},
                     {"budget (LSB)", at(d, {"budget_lsb"})},
                     {"points", json(points.is_array() ? points.size() : 0)},
                     {"area metric", at(d, {"area_metric"})}}) +
         plot(page, in, "explore: error against area and cycles per pixel") +
         table(rows, {{"point", "point"},
                      {"config", "configuration"},
                      {"max", "max LSB"},
                      {"mean", "mean LSB"},
                      {"area", "area"},
                      {"cpp", "cycles/px"}});
}

// Every key cycles writes, whatever it is: the breakdown as its table, other lists of rows
// (per-triangle figures, ...) as tables of their own, the rest as figures.
std::string cycles_section(const ReportInput& in) {
  const json& d = in.doc;
  std::string h = "<h3>" + esc(scene_name(d)) + "</h3>\n" + source(in);
  std::vector<std::pair<std::string, json>> figures;
  std::string tables;
  for (const auto& [k, v] : d.items()) {
    if (k == "scene" || k == "config" || k == "breakdown") continue;
    if (v.is_array() && !v.empty() && v.front().is_object()) {
      tables += "<h4>" + esc(plain(k)) + "</h4>\n" + table(v, {});
    } else if (v.is_object()) {
      flatten(v, k + ".", figures);
    } else {
      figures.emplace_back(k, v);
    }
  }
  for (auto& f : figures) f.first = plain(f.first);
  h += "<h4>breakdown</h4>\n" +
       table(d["breakdown"],
             {{"name", "reason"}, {"cycles", "cycles"}, {"percent", "%"}, {"meaning", "meaning"}});
  h += tables + "<h4>figures</h4>\n" + key_values(figures);
  return h;
}

// One row per cycles input: cycles per pixel and each breakdown reason's share, side by side.
std::string cycles_summary(const ReportPage& page) {
  json rows = json::array();
  std::vector<std::pair<std::string, std::string>> columns = {{"scene", "scene"},
                                                              {"cycles_per_pixel", "cycles/px"}};
  for (const auto& in : page.inputs.inputs) {
    if (in.kind != ReportKind::kCycles) continue;
    json row = {{"scene", scene_name(in.doc)},
                {"cycles_per_pixel", at(in.doc, {"cycles_per_pixel"})}};
    for (const auto& r : in.doc["breakdown"]) {
      const json name = at(r, {"name"});
      if (!name.is_string()) continue;
      const std::string key = name.get<std::string>();
      row[key] = at(r, {"percent"});
      if (std::none_of(columns.begin(), columns.end(),
                       [&](const auto& c) { return c.first == key; })) {
        columns.emplace_back(key, plain(key) + " %");
      }
    }
    rows.push_back(row);
  }
  if (rows.size() < 2) return "";
  return "<h3>every scene</h3>\n" + table(rows, columns);
}

std::string regress_section(const ReportInput& in) {
  const json& d = in.doc;
  std::string h = source(in) + key_values({{"passed", at(d, {"passed"})},
                                           {"mismatched", at(d, {"mismatched"})},
                                           {"errors", at(d, {"errors"})},
                                           {"skipped", at(d, {"skipped"})},
                                           {"seed", at(d, {"seed"})},
                                           {"wall seconds", at(d, {"wall_seconds"})}});
  json rows = json::array();
  std::string failures;
  for (const auto& j : d["jobs"]) {
    if (!j.is_object()) continue;
    json row = j;
    // A run that stopped early has no cycles per pixel to speak of.
    if (text(at(j, {"status"})) != "pass") row["cycles_per_pixel"] = "-";
    const json scene = at(j, {"scene"});
    row["scene"] =
        scene.is_string() ? json(fs::path(scene.get<std::string>()).stem().string()) : scene;
    rows.push_back(row);
    const std::string status = text(at(j, {"status"}));
    if (status == "mismatch" || status == "error") {
      const std::string replay = text(at(j, {"replay"}));
      failures += "<li><b>" +
                  esc(text(row["scene"]) + " x " + text(at(j, {"config"})) + " (" +
                      text(at(j, {"backend"})) + "): " + status) +
                  "</b> " + esc(text(at(j, {"message"}))) + "<br>replay: " +
                  (replay == "-" || replay.empty()
                       ? "<i>none recorded (see the log: " + esc(text(at(j, {"log"}))) + ")</i>"
                       : "<code>" + esc(replay) + "</code>") +
                  "</li>\n";
    }
  }
  h += table(rows, {{"scene", "scene"},
                    {"config", "config"},
                    {"backend", "backend"},
                    {"status", "result"},
                    {"pixels", "pixels"},
                    {"cycles", "cycles"},
                    {"cycles_per_pixel", "cycles/px"},
                    {"seconds", "wall s"},
                    {"message", "message"}});
  h += failures.empty()
           ? "<p>No failures.</p>\n"
           : "<h4>failures and their replay commands</h4>\n<ul>" + failures + "</ul>\n";
  return h;
}

// The Silicon section: each unit's area, clock, energy and layout beside its error and cycles.
// A unit is its `config` (the UnitConfig every command writes): area, layout, render and cycles
// JSON of one unit carry the same object. A file without one is matched by its scene instead.

// The scene a report was made on: render's and cycles's `scene`, or area's and layout's `source`
// when it names one ("scenes/sphere.json (its own configuration; ...)"); empty when unknown.
std::string scene_of(const ReportInput& in) {
  const json scene = at(in.doc, {"scene"});
  if (scene.is_string()) return scene.get<std::string>();
  const json source = at(in.doc, {"source"});
  if (!source.is_string()) return "";
  const std::string s = source.get<std::string>();
  const std::string path = s.substr(0, s.find(" ("));
  return s.find(" (") != std::string::npos ? path : "";
}

bool same_unit(const ReportInput& a, const ReportInput& b) {
  const json ca = at(a.doc, {"config"});
  const json cb = at(b.doc, {"config"});
  if (ca.is_object() && cb.is_object()) return ca == cb;
  const std::string sa = scene_of(a);
  return !sa.empty() && fs::path(sa).stem() == fs::path(scene_of(b)).stem();
}

struct SiliconUnit {
  std::vector<const ReportInput*> area, layout, render, cycles;
  const ReportInput& first() const { return area.empty() ? *layout.front() : *area.front(); }
};

std::vector<SiliconUnit> silicon_units(const ReportPage& page) {
  std::vector<SiliconUnit> units;
  for (const auto& in : page.inputs.inputs) {
    if (in.kind != ReportKind::kArea && in.kind != ReportKind::kLayout) continue;
    auto it = std::find_if(units.begin(), units.end(),
                           [&](const SiliconUnit& u) { return same_unit(u.first(), in); });
    if (it == units.end()) it = units.insert(units.end(), SiliconUnit{});
    (in.kind == ReportKind::kArea ? it->area : it->layout).push_back(&in);
  }
  for (auto& u : units) {
    for (const auto& in : page.inputs.inputs) {
      if (in.kind == ReportKind::kRender && same_unit(u.first(), in)) u.render.push_back(&in);
      if (in.kind == ReportKind::kCycles && same_unit(u.first(), in)) u.cycles.push_back(&in);
    }
  }
  return units;
}

// "the unit of sphere" from the scene its reports name, else the file the unit came from.
std::string unit_name(const SiliconUnit& u) {
  for (const auto* list : {&u.area, &u.layout, &u.render, &u.cycles}) {
    for (const ReportInput* in : *list) {
      const std::string scene = scene_of(*in);
      if (!scene.empty()) return "the unit of " + fs::path(scene).stem().string();
    }
  }
  const json source = at(u.first().doc, {"source"});
  return source.is_string() ? "unit " + source.get<std::string>() : "unit of " + u.first().path;
}

// A figure per report of a list, "1 (sphere); 2 (torus)" when the unit ran on several scenes.
json per_scene(const std::vector<const ReportInput*>& list,
               std::initializer_list<const char*> keys) {
  if (list.empty()) return nullptr;
  if (list.size() == 1) return at(list.front()->doc, keys);
  std::string joined;
  for (const ReportInput* in : list) {
    joined += (joined.empty() ? "" : "; ") + text(at(in->doc, keys)) + " (" +
              fs::path(scene_of(*in)).stem().string() + ")";
  }
  return joined;
}

// Pre-route "meets": as config judges a rung, Fmax less the guard band reaches the clock; the
// clock is the analysis period's (area times every unit at config's default clock).
json preroute_meets(const json& lib, bool brief = false) {
  const json fmax = at(lib, {"fmax_mhz"});
  const json period = at(lib, {"period_ns"});
  const json band = at(lib, {"constraints", "guard_band"});
  if (!fmax.is_number() || !period.is_number() || !band.is_number() || period.get<double>() <= 0) {
    return nullptr;
  }
  const double clock = 1000.0 / period.get<double>();
  const double reach = fmax.get<double>() * (1.0 - band.get<double>());
  if (brief) return std::string(reach >= clock ? "met " : "missed ") + text(json(clock)) + " MHz";
  return std::string(reach >= clock ? "met" : "missed") + " (" + text(json(reach)) +
         " MHz after the " + text(json(100.0 * band.get<double>())) + " % guard band, against " +
         text(json(clock)) + " MHz)";
}

// "from -> to" of a critical path; null when the report names neither.
json path_ends(const json& from, const json& to) {
  return from.is_null() && to.is_null() ? json(nullptr) : json(text(from) + " -> " + text(to));
}

json percent(const json& fraction) {
  return fraction.is_number() ? json(text(json(100.0 * fraction.get<double>())) + " %")
                              : json(nullptr);
}

std::string sources(const SiliconUnit& u) {
  std::string h;
  for (const auto* list : {&u.area, &u.layout, &u.render, &u.cycles})
    for (const ReportInput* in : *list) h += source(*in);
  return h;
}

std::string area_figures(const ReportInput& in) {
  const json& d = in.doc;
  const json lib = at(d, {"liberty"});
  std::string h = "<h4>pre-route (" + esc(in.path) + ", area --json)</h4>\n";
  std::vector<std::pair<std::string, json>> rows = {
      {"generic GE (NAND2 eq., a convention)", at(d, {"gate_equivalents"})},
      {"generic cells", at(d, {"cells"})},
      {"flip-flops", at(d, {"flip_flops"})},
      {"iCE40 HX8K Fmax (MHz)", at(d, {"ice40", "fmax_mhz"})}};
  if (!lib.is_object()) {
    return h + key_values(rows) +
           "<p class=\"missing\">no standard-cell figures: this area --json has no liberty "
           "object (area ran with --no-liberty)</p>\n";
  }
  const json c = at(lib, {"constraints"});
  const std::vector<std::pair<std::string, json>> library = {
      {"library", at(lib, {"library"})},
      {"area (um^2)", at(lib, {"area_um2"})},
      {"NAND2 eq. (library)", at(lib, {"nand2_equivalents"})},
      {"library cells", at(lib, {"cells"})},
      {"Fmax pre-route (MHz)", at(lib, {"fmax_mhz"})},
      {"analysis period (ns)", at(lib, {"period_ns"})},
      {"worst slack (ns)", at(lib, {"worst_slack_ns"})},
      {"meets the analysis clock", preroute_meets(lib)},
      {"clock uncertainty (ns)", at(c, {"clock_uncertainty_ns"})},
      {"guard band", percent(at(c, {"guard_band"}))},
      {"inputs driven by", at(c, {"input_driving_cell"})},
      {"input delay (ns)", at(c, {"input_delay_ns"})},
      {"output load (pF)", at(c, {"output_load_pf"})},
      {"output delay (ns)", at(c, {"output_delay_ns"})},
      {"critical path",
       path_ends(at(lib, {"critical_path", "from"}), at(lib, {"critical_path", "to"}))},
      {"cycles/px (area's scene)", at(lib, {"cycles_per_pixel"})},
      {"Mpixel/s at Fmax", at(lib, {"mpixel_per_s"})},
      {"energy (pJ/pixel)", at(lib, {"pj_per_pixel"})},
      {"power at Fmax (mW)", at(lib, {"mw_at_fmax"})}};
  rows.insert(rows.end(), library.begin(), library.end());
  h += key_values(rows);
  if (!c.is_object()) {
    h += "<p class=\"missing\">constraints: not recorded in this area --json (no "
         "liberty.constraints)</p>\n";
  }
  if (!at(lib, {"pj_per_pixel"}).is_number()) {
    h += "<p class=\"missing\">energy: not in this area --json (area ran without a scene, or "
         "with --no-power)</p>\n";
  }
  return h;
}

std::string layout_figures(const ReportInput& in) {
  const json& d = in.doc;
  std::string layers;
  const json by_layer = at(d, {"wire_length_by_layer_um"});
  if (by_layer.is_object()) {
    for (const auto& [layer, um] : by_layer.items())
      layers += (layers.empty() ? "" : ", ") + layer + " " + text(um);
  }
  const json lvs_clean = at(d, {"lvs", "clean"});
  const std::vector<std::pair<std::string, json>> rows = {
      {"die (um)",
       json(text(at(d, {"die", "width_um"})) + " x " + text(at(d, {"die", "height_um"})))},
      {"die area (mm^2)", at(d, {"die", "area_mm2"})},
      {"die area (um^2)", at(d, {"die", "area_um2"})},
      {"placement density", at(d, {"density"})},
      {"core area (um^2)", at(d, {"core_area_um2"})},
      {"cell area (um^2)", at(d, {"cell_area_um2"})},
      {"utilisation", percent(at(d, {"utilisation"}))},
      {"cells (+ FILL)", json(text(at(d, {"cells"})) + " (+ " + text(at(d, {"fill_cells"})) + ")")},
      {"wire length (um)", at(d, {"wire_length_um"})},
      {"wire length by layer (um)", layers.empty() ? json(nullptr) : json(layers)},
      {"vias", at(d, {"vias"})},
      {"clock (MHz)", at(d, {"clock_mhz"})},
      {"worst slack post-route (ns)", at(d, {"timing", "worst_slack_ns"})},
      {"meets the clock post-route", at(d, {"timing", "meets_clock"})},
      {"Fmax post-route (MHz)", at(d, {"timing", "fmax_mhz"})},
      {"Fmax, same netlist without wires (MHz)", at(d, {"timing", "no_wires_fmax_mhz"})},
      {"critical path", path_ends(at(d, {"timing", "path_from"}), at(d, {"timing", "path_to"}))},
      {"its wire delay (ns)", at(d, {"timing", "path_wire_delay_ns"})},
      {"unannotated nets (SPEF)", at(d, {"annotation", "unannotated_nets"})},
      {"DRC errors (magic)", at(d, {"drc", "errors"})},
      {"LVS (netgen)", lvs_clean.is_boolean()
                           ? json(std::string(lvs_clean.get<bool>() ? "clean" : "NOT clean") +
                                  " (" + text(at(d, {"lvs", "verdict"})) + ")")
                           : json(nullptr)},
      {"GDS", at(d, {"files", "gds"})},
      {"wall time when measured (s)", at(d, {"seconds"})}};
  std::string h = "<h4>post-route (" + esc(in.path) + ", layout --json)</h4>\n" + key_values(rows);
  const json png = at(d, {"files", "png"});
  h += png.is_string() ? image(locate(png.get<std::string>(), in.path),
                               "the layout: cells grey, FILL darker; metal1 blue, metal2 red, "
                               "metal3 green, metal4 yellow, metal5 cyan, metal6 white")
                       : "<p class=\"missing\">" + esc(in.path) +
                             ": no files.png (expected the path of layout's PNG)</p>";
  return h + "\n";
}

// One row per unit, the headline figures side by side; the details follow per unit.
json silicon_row(const SiliconUnit& u) {
  const json* area = u.area.empty() ? nullptr : &u.area.front()->doc;
  const json* layout = u.layout.empty() ? nullptr : &u.layout.front()->doc;
  const json none = nullptr;
  const json& a = area ? *area : none;
  const json& l = layout ? *layout : none;
  return {{"unit", unit_name(u)},
          {"max_lsb", per_scene(u.render, {"error", "max_code_lsb"})},
          {"cpp", per_scene(u.cycles, {"cycles_per_pixel"})},
          {"ge", at(a, {"gate_equivalents"})},
          {"um2", at(a, {"liberty", "area_um2"})},
          {"fmax", at(a, {"liberty", "fmax_mhz"})},
          {"meets", preroute_meets(at(a, {"liberty"}), true)},
          {"pj", at(a, {"liberty", "pj_per_pixel"})},
          {"die", at(l, {"die", "area_mm2"})},
          {"util", percent(at(l, {"utilisation"}))},
          {"post", at(l, {"timing", "fmax_mhz"})},
          {"drc", at(l, {"drc", "errors"})},
          {"lvs", at(l, {"lvs", "clean"}).is_boolean()
                      ? json(at(l, {"lvs", "clean"}).get<bool>() ? "clean" : "NOT clean")
                      : json(nullptr)}};
}

std::string silicon_unit(const SiliconUnit& u) {
  std::string h = "<h3>" + esc(unit_name(u)) + "</h3>\n" + sources(u);
  std::string missing;
  if (u.render.empty()) missing += "<li>no render --json of this unit: no error figure</li>";
  if (u.cycles.empty()) missing += "<li>no cycles --json of this unit: no cycles/px</li>";
  if (u.area.empty()) {
    missing +=
        "<li>no area --json given: no area, pre-route clock or energy "
        "(<code>shadesim area SCENE --json FILE</code>)</li>";
  }
  if (u.layout.empty()) {
    missing +=
        "<li>no layout --json given: no die, wires, post-route clock, DRC, LVS or "
        "picture (<code>shadesim layout SCENE --json FILE</code>)</li>";
  }
  if (!missing.empty()) h += "<ul class=\"missing\">" + missing + "</ul>\n";
  for (const ReportInput* in : u.area) h += area_figures(*in);
  for (const ReportInput* in : u.layout) h += layout_figures(*in);
  return h;
}

std::string silicon_section(const ReportPage& page) {
  const std::vector<SiliconUnit> units = silicon_units(page);
  if (units.empty()) {
    return "<p class=\"missing\">No input: no area --json or layout --json file was given or "
           "found. <code>shadesim area scenes/sphere.json --json out/sphere/area.json</code> and "
           "<code>shadesim layout scenes/sphere.json --json out/sphere/layout.json</code> write "
           "them (or <code>shadesim report --run area,layout</code>).</p>\n";
  }
  json rows = json::array();
  std::string details;
  for (const auto& u : units) {
    try {
      rows.push_back(silicon_row(u));
      details += silicon_unit(u);
    } catch (const std::exception& e) {
      details += "<p class=\"problem\">" + esc(u.first().path) + ": unexpected contents for " +
                 writer_of(u.first().kind) + " (" + esc(e.what()) + ")</p>\n";
    }
  }
  return "<p>Each unit's error (render --json) and cycles (cycles --json) beside its silicon "
         "(area --json: osu018 pre-route; layout --json: placed and routed). \"-\": the input "
         "does not hold the figure.</p>\n" +
         table(rows, {{"unit", "unit"},
                      {"max_lsb", "max LSB"},
                      {"cpp", "cycles/px"},
                      {"ge", "GE"},
                      {"um2", "osu018 um^2"},
                      {"fmax", "Fmax pre-route MHz"},
                      {"meets", "pre-route clock (guard band)"},
                      {"pj", "pJ/pixel"},
                      {"die", "die mm^2"},
                      {"util", "utilisation"},
                      {"post", "Fmax post-route MHz"},
                      {"drc", "DRC errors"},
                      {"lvs", "LVS"}}) +
         details;
}

std::string section(const std::string& title, const std::string& body) {
  std::string id;
  for (char c : title)
    id += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '-';
  return "<section id=\"" + id + "\">\n<h2>" + esc(title) + "</h2>\n" + body + "</section>\n";
}

// One kind's inputs, each guarded: a file with the right keys but odd contents says so.
template <typename F>
std::string kind_body(const ReportPage& page, std::initializer_list<ReportKind> kinds,
                      const std::string& recipe, F body) {
  std::string h;
  for (const auto& in : page.inputs.inputs) {
    if (std::find(kinds.begin(), kinds.end(), in.kind) == kinds.end()) continue;
    try {
      h += body(in);
    } catch (const std::exception& e) {
      h += "<p class=\"problem\">" + esc(in.path) + ": unexpected contents for " +
           writer_of(in.kind) + " (" + esc(e.what()) + ")</p>\n";
    }
  }
  return h.empty() ? none(*kinds.begin(), recipe) : h;
}

const char* kStyle =
    "body{font-family:sans-serif;margin:1.5em;max-width:1400px;color:#222}"
    "table{border-collapse:collapse;margin:.5em 0 1em}td,th{border:1px solid #bbb;padding:2px 8px;"
    "text-align:left;font-size:90%}th{background:#eee}table.kv th{width:18em}"
    ".swatch,.bar{display:inline-block;height:1em;vertical-align:middle;border:1px solid #888}"
    ".swatch{width:1em}.bar{width:12em;background:linear-gradient(to right,#0000ff,#00ff00,"
    "#ffff00,#ff0000)}.verdict{font-size:120%;padding:.4em;border:2px solid #888}"
    ".verdict.fail{border-color:#c00}.verdict.pass{border-color:#080}"
    "img{max-width:100%;border:1px solid #ccc;image-rendering:pixelated}"
    ".missing{color:#865;font-style:italic}.problem{color:#b00}.source,.caption{color:#666;font-"
    "size:85%}"
    "code{background:#f4f4f4;padding:1px 3px}section{margin-bottom:2em}";

}  // namespace

// The page's first line: the regression's totals over every regress input, the worst render
// error, and the inputs that could not be read.
std::string verdict(const ReportPage& page) {
  int64_t runs = 0, failed = 0, renders = 0;
  double worst = -1;
  std::string worst_scene;
  auto count = [](const json& d, const char* key) {
    const json v = at(d, {key});
    return v.is_number_integer() ? v.get<int64_t>() : int64_t{0};
  };
  for (const auto& in : page.inputs.inputs) {
    if (in.kind == ReportKind::kRegress) {
      const int64_t bad = count(in.doc, "mismatched") + count(in.doc, "errors") +
                          count(in.doc, "hangs") + count(in.doc, "timeouts") +
                          count(in.doc, "missing");
      runs += count(in.doc, "passed") + bad;
      failed += bad;
    } else if (in.kind == ReportKind::kRender) {
      ++renders;
      const json e = at(in.doc, {"error", "max_code_lsb"});
      if (e.is_number() && e.get<double>() > worst) {
        worst = e.get<double>();
        worst_scene = scene_name(in.doc);
      }
    }
  }
  const size_t problems = page.inputs.problems.size();
  const bool fail = failed > 0 || problems > 0;
  std::string v =
      runs > 0
          ? (failed > 0 ? std::to_string(failed) + " of " + std::to_string(runs) +
                              " regression runs failed"
                        : "all " + std::to_string(runs) + " regression runs bit- and cycle-exact")
          : "no regression among the inputs";
  if (renders > 0) {
    v +=
        "; " + std::to_string(renders) + " render(s)" +
        (worst >= 0 ? ", worst max error " + text(json(worst)) + " LSB (" + worst_scene + ")" : "");
  }
  v += "; " + std::to_string(problems) + " input(s) could not be read";
  const char* word = fail ? "FAIL" : (runs > 0 ? "PASS" : "no verdict");
  return "<p class=\"verdict " + std::string(fail ? "fail" : (runs > 0 ? "pass" : "none")) +
         "\" id=\"verdict\"><b>Verdict: " + word + "</b>: " + esc(v) + ".</p>\n";
}

const std::vector<std::string>& report_sections() {
  static const std::vector<std::string> titles = {"Inputs",
                                                  "Scenes: model, reference, error",
                                                  "Specular units: error against cost",
                                                  "Width exploration",
                                                  "Cycles per pixel",
                                                  "Silicon: area, clock, energy, layout",
                                                  "Regression",
                                                  "Tool versions"};
  return titles;
}

std::string report_html(const ReportPage& page) {
  const auto& t = report_sections();
  std::string inputs;
  if (!page.run_notes.empty()) {
    inputs += "<h4>--run</h4><ul>";
    for (const auto& n : page.run_notes) inputs += "<li>" + esc(n) + "</li>";
    inputs += "</ul>\n";
  }
  if (!page.inputs.problems.empty()) {
    inputs += "<h4>problems</h4><ul>";
    for (const auto& p : page.inputs.problems) {
      inputs +=
          "<li class=\"problem\"><code>" + esc(p.path) + "</code>: " + esc(p.message) + "</li>";
    }
    inputs += "</ul>\n";
  }
  inputs += "<h4>read</h4><ul>";
  for (const auto& in : page.inputs.inputs) {
    inputs += "<li><code>" + esc(in.path) + "</code> (" + writer_of(in.kind) + ")</li>";
  }
  inputs += page.inputs.inputs.empty() ? "<li class=\"missing\">nothing</li></ul>\n" : "</ul>\n";
  if (!page.inputs.ignored.empty()) {
    inputs += "<details><summary>" + std::to_string(page.inputs.ignored.size()) +
              " file(s) found in the folders but not reports</summary><ul>";
    for (const auto& p : page.inputs.ignored)
      inputs += "<li><code>" + esc(p.path) + "</code>: " + esc(p.message) + "</li>";
    inputs += "</ul></details>\n";
  }

  std::string tools = "<table class=\"kv\">";
  for (const auto& tv : page.tools)
    tools += "<tr><th>" + esc(tv.tool) + "</th><td>" + esc(tv.version) + "</td></tr>";
  tools += "</table>\n";

  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<title>shadesim report</title>\n<style>" +
      std::string(kStyle) +
      "</style></head><body>\n"
      "<h1>shadesim report</h1>\n<p>Generated " +
      esc(page.generated) +
      " by <code>shadesim report</code> from the JSON the other commands write.</p>\n" +
      verdict(page);
  h += section(t[0], inputs);
  h += section(t[1], kind_body(page, {ReportKind::kRender, ReportKind::kRenderUnits},
                               "<code>scripts/render</code> writes out/&lt;scene&gt;/render.json.",
                               [](const ReportInput& in) {
                                 return in.kind == ReportKind::kRender ? render_section(in)
                                                                       : render_units_section(in);
                               }));
  h += section(
      t[2],
      kind_body(
          page, {ReportKind::kSpecError},
          "<code>shadesim spec-error --json out/spec-error/spec-error.json</code> writes one.",
          [&](const ReportInput& in) { return spec_error_section(page, in); }));
  h += section(t[3], kind_body(page, {ReportKind::kExplore},
                               "<code>shadesim explore scenes/sphere.json --json "
                               "out/explore/sphere.json</code> writes one.",
                               [&](const ReportInput& in) { return explore_section(page, in); }));
  std::string summary;
  try {
    summary = cycles_summary(page);
  } catch (const std::exception& e) {
    summary =
        "<p class=\"problem\">cycles summary: unexpected contents (" + esc(e.what()) + ")</p>\n";
  }
  h += section(
      t[4],
      summary +
          kind_body(
              page, {ReportKind::kCycles},
              "<code>shadesim cycles SCENE --json out/&lt;scene&gt;/cycles.json</code> writes one.",
              [](const ReportInput& in) { return cycles_section(in); }));
  h += section(t[5], silicon_section(page));
  h += section(t[6], kind_body(page, {ReportKind::kRegress},
                               "<code>scripts/run</code> writes out/regress/regress.json.",
                               [](const ReportInput& in) { return regress_section(in); }));
  h += section(t[7], tools);
  return h + "</body></html>\n";
}

}  // namespace shadesim
