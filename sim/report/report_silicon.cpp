#include "sim/report/report_silicon.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/report/page_html.h"

namespace shadesim {
namespace fs = std::filesystem;

namespace {

using nlohmann::json;
using namespace page_html;

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

}  // namespace

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

}  // namespace shadesim
