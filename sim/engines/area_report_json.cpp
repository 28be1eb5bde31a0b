// shadesim area's report as JSON: the `--json` format and the cache entry of the generic and
// iCE40 flows (the liberty flow's entry is its own: sim/eda/sta/liberty_flow.h).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "model/text_file.h"
#include "sim/eda/yosys/area_generic.h"
#include "sim/engines/area_report.h"

namespace shadesim {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

Json params_json(const std::vector<VerilogParameter>& ps) {
  Json j = Json::array();
  for (const auto& p : ps) {
    if (p.slots.empty())
      j.push_back({{"name", p.name}, {"value", p.value}});
    else
      j.push_back({{"name", p.name}, {"slots", p.slots}});
  }
  return j;
}

}  // namespace

std::string area_report_to_json(const AreaReport& r) {
  Json modules = Json::array();
  for (const auto& m : r.modules) {
    modules.push_back({{"module", m.module},
                       {"instances", m.instances},
                       {"cells_each", m.cells_each},
                       {"transistors_each", m.transistors_each},
                       {"flip_flops_each", m.flip_flops_each},
                       {"cells", m.cells()},
                       {"transistors", m.transistors()}});
    modules.back()["logic_transistors_each"] = m.logic_transistors_each;
    modules.back()["ram_bits_each"] = m.ram_bits_each;
    modules.back()["gate_equivalents_each"] = m.gate_equivalents_each();
    modules.back()["gate_equivalents"] = m.gate_equivalents();
  }
  Json ice40 = {{"lut4", r.ice40.lut4},           {"dff", r.ice40.dff},
                {"carry", r.ice40.carry},         {"ram4k", r.ice40.ram4k},
                {"fits_hx8k", r.ice40.fits_hx8k}, {"fit_note", r.ice40.fit_note},
                {"pnr_note", r.ice40.pnr_note},   {"critical_path", r.ice40.critical_path}};
  ice40["fmax_mhz"] = r.ice40.fmax_mhz ? Json(*r.ice40.fmax_mhz) : Json(nullptr);
  Json j = {{"parameters", params_json(r.parameters)},
            {"key", r.key},
            {"from_cache", r.from_cache},
            {"yosys_version", r.yosys_version},
            {"nextpnr_version", r.nextpnr_version},
            {"cells", r.cells},
            {"transistors", r.transistors},
            {"transistors_exclude_flip_flops", r.transistors_partial},
            {"flip_flops", r.flip_flops},
            {"breakdown_cells", r.breakdown_cells},
            {"modules", modules},
            {"ice40", ice40},
            {"logic_depth",
             {{"gates", r.logic_depth.gates},
              {"from", r.logic_depth.from},
              {"to", r.logic_depth.to},
              {"method", LogicDepth::kMethod}}},
            {"seconds", r.seconds},
            {"cpu_seconds", r.cpu_seconds},
            {"warnings", r.warnings}};
  // GE: NAND2 gate equivalents = logic_transistors / 4 + 6 per flip-flop outside the RAM
  // (sim/eda/yosys/generic_area.h); ram_bits: the table memories, apart.
  j["logic_transistors"] = r.logic_transistors;
  j["ram_bits"] = r.ram_bits;
  j["ram_bits_expected"] = r.ram_bits_expected;
  j["gate_equivalents"] = r.gate_equivalents();
  j["gate_equivalents_convention"] =
      "NAND2 GE = (stat -tech cmos transistors less its flip-flop cost) / 4 + 6 per flip-flop; "
      "table memory bits apart (ram_bits), not flip-flops";
  if (r.liberty) j["liberty"] = Json::parse(liberty_report_to_json(*r.liberty));
  return j.dump(2) + "\n";
}

AreaReport area_report_from_json(const std::string& text, const std::string& source) {
  try {
    const Json j = Json::parse(text);
    AreaReport r;
    for (const auto& p : j.at("parameters")) {
      if (p.contains("slots"))
        r.parameters.emplace_back(p.at("name").get<std::string>(),
                                  p.at("slots").get<std::vector<int64_t>>());
      else
        r.parameters.emplace_back(p.at("name").get<std::string>(), p.at("value").get<int64_t>());
    }
    r.key = j.at("key");
    r.from_cache = j.at("from_cache");
    r.yosys_version = j.at("yosys_version");
    r.nextpnr_version = j.at("nextpnr_version");
    r.cells = j.at("cells");
    r.transistors = j.at("transistors");
    r.transistors_partial = j.at("transistors_exclude_flip_flops");
    r.flip_flops = j.at("flip_flops");
    r.breakdown_cells = j.at("breakdown_cells");
    for (const auto& m : j.at("modules")) {
      r.modules.push_back({m.at("module"), m.at("instances"), m.at("cells_each"),
                           m.at("transistors_each"), m.at("flip_flops_each")});
      r.modules.back().logic_transistors_each = m.at("logic_transistors_each");
      r.modules.back().ram_bits_each = m.at("ram_bits_each");
    }
    r.logic_transistors = j.at("logic_transistors");
    r.ram_bits = j.at("ram_bits");
    r.ram_bits_expected = j.at("ram_bits_expected");
    const Json& d = j.at("logic_depth");
    r.logic_depth = {d.at("gates").get<int64_t>(), d.at("from"), d.at("to")};
    const Json& a = j.at("ice40");
    r.ice40.lut4 = a.at("lut4");
    r.ice40.dff = a.at("dff");
    r.ice40.carry = a.at("carry");
    r.ice40.ram4k = a.at("ram4k");
    r.ice40.fits_hx8k = a.at("fits_hx8k");
    r.ice40.fit_note = a.at("fit_note");
    r.ice40.pnr_note = a.at("pnr_note");
    r.ice40.critical_path = a.value("critical_path", "");  // entries before it was recorded
    if (!a.at("fmax_mhz").is_null()) r.ice40.fmax_mhz = a.at("fmax_mhz").get<double>();
    r.seconds = j.at("seconds");
    r.cpu_seconds = j.at("cpu_seconds");
    if (j.contains("warnings")) r.warnings = j.at("warnings").get<std::vector<std::string>>();
    if (j.contains("liberty")) r.liberty = liberty_report_from_json(j.at("liberty").dump(), source);
    return r;
  } catch (const Json::exception& e) {
    throw std::runtime_error(source + ": not an area report: " + e.what());
  }
}

std::vector<AreaReport> load_area_reports(const std::string& cache_dir) {
  std::vector<AreaReport> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(cache_dir, ec)) {
    if (!e.is_regular_file() || e.path().extension() != ".json") continue;
    // The liberty flow's entries (liberty-KEY.json) are not area reports.
    if (e.path().filename().string().rfind("liberty-", 0) == 0) continue;
    try {
      AreaReport r = area_report_from_json(read_text_file((e.path()).string()), e.path().string());
      generic_flow::check_series(r);
      out.push_back(std::move(r));
    } catch (const std::exception&) {
      // not an area report (or an older format): not an anchor
    }
  }
  return out;
}

}  // namespace shadesim
