// The inputs of `shadesim report`: the JSON the other commands write, found in the files and
// folders given (or the usual output folder), each recognised by its keys. The one place that
// knows which command wrote a JSON file.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace shadesim {

enum class ReportKind {
  kRender,
  kRenderUnits,
  kSpecError,
  kExplore,
  kCycles,
  kRegress,
  kArea,
  kLayout
};

// The command whose --json wrote a report of this kind, e.g. "render --json".
const char* writer_of(ReportKind kind);

struct ReportInput {
  std::string path;
  ReportKind kind;
  nlohmann::json doc;
};

// A file that was named or found but cannot be used, and why (names the file and what was
// expected). `named`: given on the command line (a problem), not just found in a folder.
struct InputNote {
  std::string path;
  std::string message;
  bool named = false;
};

struct ReportInputs {
  std::vector<ReportInput> inputs;  // in path order
  std::vector<InputNote> problems;  // missing or malformed: shown first on the page
  std::vector<InputNote> ignored;   // found in a folder, but not a report (e.g. a unit config)
};

// What kind of report a parsed JSON document is, from its keys; empty when none.
std::optional<ReportKind> classify_report(const nlohmann::json& doc);

// Why a report of this kind cannot be shown (a figure the page reads is there but of the wrong
// type, or a required one is missing), naming the field and what was expected; empty when it can.
// Only the silicon reports are checked this deeply: the page reads their figures one by one.
std::string report_shape_problem(ReportKind kind, const nlohmann::json& doc);

// Reads every path: a file is read and classified; a folder contributes its *.json files and
// those one folder down (out/<scene>/render.json, out/regress/regress.json; deeper files such as
// regress's per-run results/ are not reports). Never throws for bad input: it becomes a note.
ReportInputs find_report_inputs(const std::vector<std::string>& paths);

}  // namespace shadesim
