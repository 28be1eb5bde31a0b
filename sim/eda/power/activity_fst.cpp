// Toggles and time at 1 of every bit of an FST waveform (sim/eda/power/activity.h,
// read_fst_activity), with the FST reader Verilator ships (gtkwave's fstapi, compiled by
// activity_fstapi.cpp).
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/eda/power/activity.h"

#ifdef SHADESIM_HAVE_FSTAPI
#include "gtkwave/fstapi.h"
#endif

namespace shadesim {
namespace activity_fst_impl {

// One traced variable (all the names it is declared under share its handle).
struct Trace {
  size_t width = 0;
  std::vector<std::vector<std::string>> bit_names;  // per name: bit k of the value string
  std::string value;                                // the current value (MSB first)
  uint64_t since = 0;                               // time of the last change
  std::vector<uint64_t> toggles, time_high;         // per character of the value string
};

// "d_q [22:0]" -> base "d_q", msb 22, lsb 0; "x" -> base "x", no range.
void split_var(const std::string& name, std::string& base, int& msb, int& lsb, bool& ranged) {
  const auto sp = name.rfind(" [");
  ranged = sp != std::string::npos && name.back() == ']';
  base = ranged ? name.substr(0, sp) : name;
  msb = lsb = 0;
  if (!ranged) return;
  const std::string r = name.substr(sp + 2, name.size() - sp - 3);
  const auto colon = r.find(':');
  msb = std::stoi(r.substr(0, colon));
  lsb = colon == std::string::npos ? msb : std::stoi(r.substr(colon + 1));
}

// The names of the characters of a value string (MSB first).
std::vector<std::string> bit_names(const std::string& path, const std::string& var, size_t width) {
  std::string base;
  int msb = 0, lsb = 0;
  bool ranged = false;
  split_var(var, base, msb, lsb, ranged);
  std::vector<std::string> out;
  if (!ranged) {
    out.push_back(path + base);
    return out;
  }
  const int step = msb >= lsb ? -1 : 1;
  for (size_t i = 0; i < width; ++i)
    out.push_back(path + base + "[" + std::to_string(msb + step * static_cast<int>(i)) + "]");
  return out;
}

void change(Trace& t, uint64_t time, const char* v) {
  if (t.value.empty()) {  // the first value: the baseline, no toggle
    t.value.assign(v, t.width);
    t.since = time;
    return;
  }
  for (size_t i = 0; i < t.width; ++i) {
    if (t.value[i] == '1') t.time_high[i] += time - t.since;
    if (v[i] != t.value[i]) ++t.toggles[i];
    t.value[i] = v[i];
  }
  t.since = time;
}

#ifdef SHADESIM_HAVE_FSTAPI
struct Reader {
  std::map<fstHandle, Trace> traces;
};

void on_value(void* user, uint64_t time, fstHandle h, const unsigned char* v) {
  auto& traces = static_cast<Reader*>(user)->traces;
  const auto it = traces.find(h);
  if (it != traces.end() && v) change(it->second, time, reinterpret_cast<const char*>(v));
}

// Declarations under TOP.<top>: their traces, named by the path below the top.
void read_hierarchy(void* ctx, const std::string& top, Reader& r) {
  std::vector<std::string> scopes;
  while (fstHier* h = fstReaderIterateHier(ctx)) {
    if (h->htyp == FST_HT_SCOPE) {
      scopes.push_back(h->u.scope.name);
    } else if (h->htyp == FST_HT_UPSCOPE) {
      if (!scopes.empty()) scopes.pop_back();
    } else if (h->htyp == FST_HT_VAR && scopes.size() >= 2 && scopes[1] == top) {
      std::string path;
      for (size_t i = 2; i < scopes.size(); ++i) path += scopes[i] + ".";
      Trace& t = r.traces[h->u.var.handle];
      t.width = h->u.var.length;
      t.toggles.assign(t.width, 0);
      t.time_high.assign(t.width, 0);
      t.bit_names.push_back(bit_names(path, h->u.var.name, t.width));
    }
  }
}
#endif

}  // namespace activity_fst_impl

FstActivity read_fst_activity(const std::string& fst_path, const std::string& top, uint64_t tail) {
#ifndef SHADESIM_HAVE_FSTAPI
  (void)top;
  (void)tail;
  throw std::runtime_error("activity: built without Verilator's FST reader; cannot read " +
                           fst_path);
#else
  using namespace activity_fst_impl;
  void* ctx = fstReaderOpen(fst_path.c_str());
  if (!ctx) throw std::runtime_error("activity: cannot read the FST file " + fst_path);
  Reader r;
  read_hierarchy(ctx, top, r);
  FstActivity out;
  out.start_time = fstReaderGetStartTime(ctx);
  out.end_time = fstReaderGetEndTime(ctx) + tail;
  fstReaderSetFacProcessMaskAll(ctx);
  fstReaderIterBlocks(ctx, on_value, &r, nullptr);
  fstReaderClose(ctx);
  if (r.traces.empty()) throw std::runtime_error("activity: " + fst_path + " has no " + top);
  const double span = static_cast<double>(out.end_time - out.start_time);
  for (auto& [handle, t] : r.traces) {
    if (t.value.empty()) continue;
    change(t, out.end_time, t.value.c_str());  // close the last interval
    for (const auto& names : t.bit_names) {
      for (size_t i = 0; i < t.width && i < names.size(); ++i) {
        out.toggles[names[i]] = t.toggles[i];
        out.duty[names[i]] = span > 0 ? static_cast<double>(t.time_high[i]) / span : 0.0;
      }
    }
  }
  return out;
#endif
}

}  // namespace shadesim
