// regress --netlist's netlists, synthesised in the background while the host sets up the scenes.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <future>
#include <map>
#include <mutex>
#include <string>

#include "model/unit_config_file.h"
#include "sim/eda/yosys/unit_netlist.h"
#include "sim/regress/regress.h"

namespace shadesim {

// --netlist: each configuration's gate-level netlist (sim/eda/yosys/unit_netlist.h),
// synthesised in the background while the host sets up the scenes, at most `workers` Yosys runs at
// once.
class NetlistSource {
 public:
  NetlistSource(const RegressOptions& o, int workers) : workers_(std::max(1, workers)) {
    options_.cache_dir = o.netlist_cache.empty() ? default_netlist_cache_dir() : o.netlist_cache;
  }
  // Starts (once per unit) the netlist of `unit`; the token names it for get().
  std::string start(const UnitConfig& unit) {
    std::string token = config_to_json(unit);  // returned: moved
    std::lock_guard<std::mutex> lock(m_);
    if (!jobs_.count(token)) {
      jobs_.emplace(token, std::async(std::launch::async, [this, unit] {
                             Slot slot(*this);
                             return unit_netlist(unit, options_);
                           }).share());
    }
    return token;
  }
  // The netlist `token` names (waits for it); throws what its synthesis threw.
  UnitNetlist get(const std::string& token) {
    std::shared_future<UnitNetlist> f;
    {
      std::lock_guard<std::mutex> lock(m_);
      f = jobs_.at(token);
    }
    return f.get();
  }

 private:
  struct Slot {  // one of `workers_` Yosys slots
    explicit Slot(NetlistSource& s) : s(s) {
      std::unique_lock<std::mutex> lock(s.slots_m_);
      s.free_.wait(lock, [&] { return s.running_ < s.workers_; });
      ++s.running_;
    }
    ~Slot() {
      {
        std::lock_guard<std::mutex> lock(s.slots_m_);
        --s.running_;
      }
      s.free_.notify_one();
    }
    NetlistSource& s;
  };
  NetlistOptions options_;
  int workers_;
  std::mutex m_, slots_m_;
  std::condition_variable free_;
  int running_ = 0;
  std::map<std::string, std::shared_future<UnitNetlist>> jobs_;
};

}  // namespace shadesim
