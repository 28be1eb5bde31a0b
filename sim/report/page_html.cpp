// The page's building blocks (sim/report/page_html.h).
#include "sim/report/page_html.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "sim/regress/junit.h"

namespace shadesim {
namespace page_html {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

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

}  // namespace

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

// A table of the rows of an array of objects: the given columns, or every key the rows have.
std::string table(const json& rows, std::vector<std::pair<std::string, std::string>> columns,
                  size_t limit) {
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

}  // namespace page_html
}  // namespace shadesim
