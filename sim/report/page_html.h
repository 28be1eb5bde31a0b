// The building blocks of `shadesim report`'s page (sim/report/report_page.h): escaped text,
// figures as table text, tables, key/value tables and embedded PNGs.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sim/report/report_inputs.h"

namespace shadesim {
namespace page_html {

// `s` escaped for HTML text and attributes.
std::string esc(const std::string& s);

// A value of a report as table text: numbers to 4 significant digits, strings as they are,
// null as "-".
std::string text(const nlohmann::json& v);

// doc[a][b]..., or null where a key is missing or a level is not an object.
nlohmann::json at(const nlohmann::json& doc, std::initializer_list<const char*> keys);

// <td> of text(v).
std::string cell(const nlohmann::json& v);

// <img> with the PNG embedded, or a note naming the file when it cannot be read.
std::string image(const std::string& path, const std::string& alt);

// An image a report names: as written (relative to where the command ran), else beside the
// report.
std::string locate(const std::string& named, const std::string& report_path);

// The line naming the file a part of the page comes from, and the command that wrote it.
std::string source(const ReportInput& in);

// A table of the rows of an array of objects: the given (key, heading) columns, or every key the
// rows have; at most `limit` rows, then how many more there are.
std::string table(const nlohmann::json& rows,
                  std::vector<std::pair<std::string, std::string>> columns, size_t limit = 200);

// Key/value rows of an object's scalars (nested objects flattened to a.b), appended to `out`.
void flatten(const nlohmann::json& obj, const std::string& prefix,
             std::vector<std::pair<std::string, nlohmann::json>>& out);

// A two-column table of key/value rows.
std::string key_values(const std::vector<std::pair<std::string, nlohmann::json>>& rows);

}  // namespace page_html
}  // namespace shadesim
