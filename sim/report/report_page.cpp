#include "sim/report/report_page.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "sim/regress/junit.h"
#include "sim/report/page_html.h"
#include "sim/report/report_silicon.h"

namespace shadesim {
namespace fs = std::filesystem;

namespace {

using nlohmann::json;
using namespace page_html;

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
