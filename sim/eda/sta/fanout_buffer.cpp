#include "sim/eda/sta/fanout_buffer.h"

#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace shadesim {
namespace {

using Json = nlohmann::json;

// One cell input pin bit on a net.
struct FanoutSink {
  std::string cell, port;
  size_t index = 0;
};

// The direction of every pin of every cell type the module uses, and which pins are clocks.
class FanoutPinRoles {
 public:
  FanoutPinRoles(const Json& doc, const LibertyLibrary& lib, const std::string& source)
      : doc_(doc), lib_(lib), source_(source) {}

  bool is_input(const Json& cell, const std::string& type, const std::string& port) const {
    if (const auto it = lib_.cells.find(type); it != lib_.cells.end()) {
      const LibertyPin* p = it->second.pin(port);
      if (!p) throw error(type, "has no pin " + port + " in the library");
      return p->direction == "input";
    }
    const std::string module_key = doc_.at("modules").contains(type) ? type : "";
    if (!module_key.empty()) {
      const Json& ports = doc_.at("modules").at(module_key).at("ports");
      if (!ports.contains(port)) throw error(type, "has no port " + port);
      return ports.at(port).at("direction") == "input";
    }
    if (cell.contains("port_directions") && cell.at("port_directions").contains(port))
      return cell.at("port_directions").at(port) == "input";
    throw error(type, "is neither a library cell nor a module of the netlist");
  }

  bool is_clock(const std::string& type, const std::string& port) const {
    const auto it = lib_.cells.find(type);
    const LibertyPin* p = it == lib_.cells.end() ? nullptr : it->second.pin(port);
    return p && p->clock;
  }

 private:
  std::runtime_error error(const std::string& type, const std::string& what) const {
    return std::runtime_error(source_ + ": cell type " + type + " " + what + " (library " +
                              lib_.path + ")");
  }
  const Json& doc_;
  const LibertyLibrary& lib_;
  std::string source_;
};

struct FanoutNetSinks {
  std::map<int64_t, std::vector<FanoutSink>> sinks;  // bit -> cell input pins, netlist order
  std::set<int64_t> clock_nets;
  int64_t last_bit = 1;
};

FanoutNetSinks collect_fanout_sinks(const Json& module, const FanoutPinRoles& roles) {
  FanoutNetSinks n;
  for (const auto& [name, net] : module.at("netnames").items()) {
    for (const auto& b : net.at("bits"))
      if (b.is_number_integer()) n.last_bit = std::max(n.last_bit, b.get<int64_t>());
  }
  for (const auto& [name, cell] : module.at("cells").items()) {
    const std::string type = cell.at("type");
    for (const auto& [port, bits] : cell.at("connections").items()) {
      if (!roles.is_input(cell, type, port)) continue;
      const bool clock = roles.is_clock(type, port);
      for (size_t i = 0; i < bits.size(); ++i) {
        if (!bits[i].is_number_integer()) continue;  // a constant
        const int64_t bit = bits[i].get<int64_t>();
        n.last_bit = std::max(n.last_bit, bit);
        n.sinks[bit].push_back({name, port, i});
        if (clock) n.clock_nets.insert(bit);
      }
    }
  }
  return n;
}

// Splits `level` into ceil(size / max) groups of near-equal size.
std::vector<std::vector<FanoutSink>> split_fanout_evenly(const std::vector<FanoutSink>& level,
                                                         size_t max) {
  const size_t groups = (level.size() + max - 1) / max;
  std::vector<std::vector<FanoutSink>> out(groups);
  for (size_t g = 0, at = 0; g < groups; ++g) {
    const size_t n = level.size() / groups + (g < level.size() % groups ? 1 : 0);
    out[g].assign(level.begin() + static_cast<long>(at), level.begin() + static_cast<long>(at + n));
    at += n;
  }
  return out;
}

// The tree of one net: each round puts every group of the current level behind a new buffer
// driven (for now) from `root`, until at most `max` loads remain on root.
void build_fanout_tree(Json& module, int64_t root, std::vector<FanoutSink> level, size_t max,
                       const LibertyCell& buffer, FanoutNetSinks& nets, FanoutBufferResult& r) {
  const std::string in = buffer.inputs()[0]->name, out = buffer.outputs()[0]->name;
  Json& cells = module.at("cells");
  while (level.size() > max) {
    std::vector<FanoutSink> next;
    for (const auto& group : split_fanout_evenly(level, max)) {
      const int64_t bit = ++nets.last_bit;
      const std::string name = "fanout_buf_" + std::to_string(r.buffers++);
      for (const auto& s : group) cells.at(s.cell).at("connections").at(s.port)[s.index] = bit;
      cells[name] = {{"hide_name", 0},
                     {"type", buffer.name},
                     {"parameters", Json::object()},
                     {"attributes", Json::object()},
                     {"connections", {{in, Json::array({root})}, {out, Json::array({bit})}}}};
      module.at("netnames")[name + "_y"] = {
          {"hide_name", 0}, {"bits", Json::array({bit})}, {"attributes", Json::object()}};
      next.push_back({name, in, 0});
    }
    level = std::move(next);
  }
}

}  // namespace

FanoutBufferResult buffer_fanout(Json& netlist, const std::string& top, const LibertyLibrary& lib,
                                 int max_fanout, const std::string& source) {
  if (max_fanout < 2)
    throw std::invalid_argument("fanout buffering: a limit of " + std::to_string(max_fanout) +
                                " loads per net cannot be met by a tree (at least 2)");
  if (!netlist.contains("modules") || !netlist.at("modules").contains(top))
    throw std::runtime_error(source + ": no module " + top + " in the netlist");
  Json& module = netlist.at("modules").at(top);
  const FanoutPinRoles roles(netlist, lib, source);
  FanoutNetSinks nets = collect_fanout_sinks(module, roles);
  const LibertyCell& buffer = strongest_buffer(lib);
  FanoutBufferResult r;
  r.buffer_cell = buffer.name;
  r.max_fanout = max_fanout;
  const size_t max = static_cast<size_t>(max_fanout);
  // The sinks are copied: build_fanout_tree adds bits (no new sinks of existing nets).
  const std::map<int64_t, std::vector<FanoutSink>> all = nets.sinks;
  for (const auto& [bit, sinks] : all) {
    r.largest_fanout = std::max<int64_t>(r.largest_fanout, static_cast<int64_t>(sinks.size()));
    if (sinks.size() <= max) continue;
    if (nets.clock_nets.count(bit)) {
      ++r.clock_nets_skipped;
      continue;
    }
    build_fanout_tree(module, bit, sinks, max, buffer, nets, r);
    ++r.nets_buffered;
  }
  return r;
}

}  // namespace shadesim
