#include "sim/report/report_inputs.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace shadesim {
namespace fs = std::filesystem;

namespace {

bool has(const nlohmann::json& doc, const char* key, nlohmann::json::value_t type) {
  const auto it = doc.find(key);
  return it != doc.end() && it->type() == type;
}

const char* kExpected =
    "expected the JSON of render, cycles, spec-error, explore, regress, area or layout --json";
const char* kJunit =
    "JUnit XML is not read: the regression table comes from regress --json (the same runs, with "
    "each failure's replay command); pass that file";

void read_file(const fs::path& path, bool named, ReportInputs& out) {
  const std::string name = path.string();
  if (path.extension() == ".xml") {
    (named ? out.problems : out.ignored).push_back({name, kJunit, named});
    return;
  }
  std::ifstream is(path);
  if (!is) {
    out.problems.push_back({name, "cannot be read (" + std::string(kExpected) + ")", named});
    return;
  }
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(is);
  } catch (const nlohmann::json::exception& e) {
    out.problems.push_back(
        {name, std::string("not valid JSON (") + e.what() + "); " + kExpected, named});
    return;
  }
  const std::optional<ReportKind> kind = classify_report(doc);
  const std::string shape = kind ? report_shape_problem(*kind, doc) : "";
  if (!shape.empty()) {
    // It has a report's keys, so it is one, and a broken one: a problem even when only found.
    out.problems.push_back({name, shape, named});
    return;
  }
  if (!kind) {
    const bool config = doc.is_object() && doc.contains("channels") && doc.contains("series");
    const std::string why = config ? std::string("a unit configuration, not a report; ") + kExpected
                                   : std::string("no report's keys; ") + kExpected;
    (named ? out.problems : out.ignored).push_back({name, why, named});
    return;
  }
  out.inputs.push_back({name, *kind, std::move(doc)});
}

void read_folder(const fs::path& dir, ReportInputs& out) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (e.is_regular_file() &&
        (e.path().extension() == ".json" || e.path().extension() == ".xml")) {
      files.push_back(e.path());
    } else if (e.is_directory()) {
      std::error_code sub_ec;
      for (const auto& f : fs::directory_iterator(e.path(), sub_ec)) {
        if (f.is_regular_file() &&
            (f.path().extension() == ".json" || f.path().extension() == ".xml")) {
          files.push_back(f.path());
        }
      }
    }
  }
  if (ec) {
    out.problems.push_back({dir.string(), "folder cannot be read: " + ec.message(), true});
    return;
  }
  std::sort(files.begin(), files.end());
  const size_t before = out.inputs.size();
  for (const auto& f : files) read_file(f, false, out);
  if (out.inputs.size() == before) {
    out.problems.push_back(
        {dir.string(),
         std::string("folder holds no report (") + kExpected + ", in it or one folder down)",
         true});
  }
}

}  // namespace

const char* writer_of(ReportKind kind) {
  switch (kind) {
    case ReportKind::kRender:
      return "render --json";
    case ReportKind::kRenderUnits:
      return "render --all-units --json";
    case ReportKind::kSpecError:
      return "spec-error --json";
    case ReportKind::kExplore:
      return "explore --json";
    case ReportKind::kCycles:
      return "cycles --json";
    case ReportKind::kRegress:
      return "regress --json";
    case ReportKind::kArea:
      return "area --json";
    case ReportKind::kLayout:
      return "layout --json";
  }
  return "?";
}

std::optional<ReportKind> classify_report(const nlohmann::json& doc) {
  using T = nlohmann::json::value_t;
  if (!doc.is_object()) return std::nullopt;
  if (doc.value("kind", std::string()) == "explore") return ReportKind::kExplore;
  if (has(doc, "breakdown", T::array) && doc.contains("cycles_per_pixel"))
    return ReportKind::kCycles;
  if (has(doc, "jobs", T::array) && doc.contains("passed")) return ReportKind::kRegress;
  if (has(doc, "exponents", T::array) && has(doc, "units", T::array)) return ReportKind::kSpecError;
  if (has(doc, "images", T::object) && has(doc, "error", T::object)) return ReportKind::kRender;
  if (has(doc, "scene", T::string) && has(doc, "units", T::array)) return ReportKind::kRenderUnits;
  if (doc.contains("gate_equivalents") && doc.contains("transistors")) return ReportKind::kArea;
  if (doc.contains("die") && doc.contains("drc") && doc.contains("lvs")) return ReportKind::kLayout;
  return std::nullopt;
}

namespace {

enum class Shape { kNumber, kNumberOrNull, kBool, kString, kObject };

struct Field {
  const char* path;  // dotted: timing.fmax_mhz
  Shape shape;
  bool required;
};

const char* shape_name(Shape s) {
  switch (s) {
    case Shape::kNumber:
      return "a number";
    case Shape::kNumberOrNull:
      return "a number or null";
    case Shape::kBool:
      return "true or false";
    case Shape::kString:
      return "a string";
    case Shape::kObject:
      return "an object";
  }
  return "?";
}

bool fits(const nlohmann::json& v, Shape s) {
  switch (s) {
    case Shape::kNumber:
      return v.is_number();
    case Shape::kNumberOrNull:
      return v.is_number() || v.is_null();
    case Shape::kBool:
      return v.is_boolean();
    case Shape::kString:
      return v.is_string();
    case Shape::kObject:
      return v.is_object();
  }
  return false;
}

// The fields the Silicon section reads (sim/report/report_page.cpp), as the commands write them
// (sim/engines/area.cpp, sim/eda/sta/liberty_flow_io.cpp, sim/eda/layout/layout_report_json.cpp).
// A missing optional field is shown as missing; a field of the wrong type is a malformed file.
const std::vector<Field>& area_fields() {
  static const std::vector<Field> f = {
      {"gate_equivalents", Shape::kNumber, true},
      {"cells", Shape::kNumber, false},
      {"flip_flops", Shape::kNumber, false},
      {"source", Shape::kString, false},
      {"config", Shape::kObject, false},
      {"liberty", Shape::kObject, false},
      {"liberty.library", Shape::kString, false},
      {"liberty.area_um2", Shape::kNumber, true},
      {"liberty.nand2_equivalents", Shape::kNumber, false},
      {"liberty.period_ns", Shape::kNumber, true},
      {"liberty.worst_slack_ns", Shape::kNumber, false},
      {"liberty.fmax_mhz", Shape::kNumber, true},
      {"liberty.cycles_per_pixel", Shape::kNumberOrNull, false},
      {"liberty.mpixel_per_s", Shape::kNumberOrNull, false},
      {"liberty.pj_per_pixel", Shape::kNumberOrNull, false},
      {"liberty.mw_at_fmax", Shape::kNumberOrNull, false},
      {"liberty.constraints", Shape::kObject, false},
      {"liberty.constraints.clock_uncertainty_ns", Shape::kNumber, true},
      {"liberty.constraints.guard_band", Shape::kNumber, true},
      {"liberty.constraints.input_driving_cell", Shape::kString, false},
      {"liberty.constraints.input_delay_ns", Shape::kNumber, false},
      {"liberty.constraints.output_load_pf", Shape::kNumber, false},
      {"liberty.constraints.output_delay_ns", Shape::kNumber, false},
      {"ice40", Shape::kObject, false},
      {"ice40.fmax_mhz", Shape::kNumberOrNull, false}};
  return f;
}

const std::vector<Field>& layout_fields() {
  static const std::vector<Field> f = {{"source", Shape::kString, false},
                                       {"config", Shape::kObject, false},
                                       {"die", Shape::kObject, true},
                                       {"die.width_um", Shape::kNumber, false},
                                       {"die.height_um", Shape::kNumber, false},
                                       {"die.area_um2", Shape::kNumber, true},
                                       {"density", Shape::kNumber, false},
                                       {"core_area_um2", Shape::kNumber, false},
                                       {"cell_area_um2", Shape::kNumber, false},
                                       {"utilisation", Shape::kNumber, false},
                                       {"wire_length_um", Shape::kNumber, false},
                                       {"vias", Shape::kNumber, false},
                                       {"clock_mhz", Shape::kNumber, false},
                                       {"timing", Shape::kObject, true},
                                       {"timing.fmax_mhz", Shape::kNumber, true},
                                       {"timing.worst_slack_ns", Shape::kNumber, false},
                                       {"timing.meets_clock", Shape::kBool, false},
                                       {"timing.no_wires_fmax_mhz", Shape::kNumber, false},
                                       {"timing.path_wire_delay_ns", Shape::kNumber, false},
                                       {"drc", Shape::kObject, true},
                                       {"drc.errors", Shape::kNumber, true},
                                       {"lvs", Shape::kObject, true},
                                       {"lvs.clean", Shape::kBool, true},
                                       {"lvs.verdict", Shape::kString, false},
                                       {"files", Shape::kObject, false},
                                       {"files.png", Shape::kString, false},
                                       {"files.gds", Shape::kString, false}};
  return f;
}

// The value at a dotted path; null when a level is missing. `parent_present`: every level above
// the last is there (a required field under an absent optional object is not required).
const nlohmann::json* find_path(const nlohmann::json& doc, const std::string& path,
                                bool* parent_present) {
  const nlohmann::json* p = &doc;
  size_t start = 0;
  *parent_present = true;
  while (true) {
    const size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? dot : dot - start);
    const bool last = dot == std::string::npos;
    if (!p->is_object() || !p->contains(key)) {
      *parent_present = last && p->is_object();
      return nullptr;
    }
    p = &(*p)[key];
    if (last) return p;
    start = dot + 1;
  }
}

}  // namespace

std::string report_shape_problem(ReportKind kind, const nlohmann::json& doc) {
  const bool area = kind == ReportKind::kArea;
  if (!area && kind != ReportKind::kLayout) return "";
  std::string bad;
  for (const Field& f : area ? area_fields() : layout_fields()) {
    bool parent_present = false;
    const nlohmann::json* v = find_path(doc, f.path, &parent_present);
    if (v ? fits(*v, f.shape) : !(f.required && parent_present)) continue;
    bad += std::string(bad.empty() ? "" : "; ") + f.path + " " +
           (v ? "is " + std::string(v->type_name()) : std::string("is missing")) + ", expected " +
           shape_name(f.shape);
  }
  if (bad.empty()) return "";
  return std::string("has the keys of ") + writer_of(kind) + " but " + bad + " (" +
         (area ? "shadesim area --json: gate_equivalents, and liberty's area_um2, period_ns, "
                 "fmax_mhz and constraints, as docs/report.md lists them"
               : "shadesim layout --json: die.area_um2, timing.fmax_mhz, drc.errors, lvs.clean, "
                 "as docs/report.md lists them") +
         ")";
}

ReportInputs find_report_inputs(const std::vector<std::string>& paths) {
  ReportInputs out;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::is_directory(p, ec)) {
      read_folder(p, out);
    } else if (fs::exists(p, ec)) {
      read_file(p, true, out);
    } else {
      out.problems.push_back(
          {p, std::string("does not exist (") + kExpected + ", or a folder of them)", true});
    }
  }
  std::stable_sort(out.inputs.begin(), out.inputs.end(),
                   [](const ReportInput& a, const ReportInput& b) { return a.path < b.path; });
  return out;
}

}  // namespace shadesim
