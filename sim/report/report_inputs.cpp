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
    "expected the JSON of render, cycles, spec-error, explore or regress --json";
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
  return std::nullopt;
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
