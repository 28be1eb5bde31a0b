#include "model/exponent_lut.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace shadesim {

namespace {
bool centred(const LutConfig& c) { return c.index == LutIndex::kTruncate && c.interp_bits == 0; }
}  // namespace

ExponentLut::ExponentLut(const LutConfig& config, const FixedFormat& series, const FixedFormat& out,
                         int banks)
    : config_(config), series_(series), out_(out) {
  if (banks != 1 && banks != 2) {
    throw std::invalid_argument("lut: " + std::to_string(banks) +
                                " material banks; expected 1 or 2");
  }
  address_.wl = config.addr_bits + config.interp_bits;
  address_.iwl = config.addr_bits;
  address_.is_signed = false;
  address_.quant =
      config.index == LutIndex::kTruncate ? Quantization::kTruncate : Quantization::kRoundNearest;
  address_.overflow = Overflow::kSaturate;
  tables_.assign(static_cast<size_t>(banks),
                 std::vector<int64_t>(static_cast<size_t>(entries()), 0));
}

void ExponentLut::load_params(const std::vector<int64_t>& unit_params) {
  const int64_t shift = unit_params.empty() ? 0 : unit_params[0];
  if (unit_params.size() > 1 || shift < 0 || shift > series_.frac_bits()) {
    throw std::invalid_argument("lut: MATERIAL unit_params must be [shift] with shift 0.." +
                                std::to_string(series_.frac_bits()));
  }
  shift_ = static_cast<int>(shift);
}

void ExponentLut::load_table(const TableCmd& t) {
  const int64_t limit = int64_t{1} << config_.entry_bits;
  for (size_t k = 0; k < t.entries.size(); ++k) {
    const uint64_t addr = t.base + k;
    if (addr >= static_cast<uint64_t>(entries())) {
      throw std::invalid_argument("lut: TABLE address " + std::to_string(addr) + " past the " +
                                  std::to_string(entries()) + "-entry table");
    }
    if (t.entries[k] < 0 || t.entries[k] >= limit) {
      throw std::invalid_argument("lut: TABLE entry at address " + std::to_string(addr) + " is " +
                                  std::to_string(t.entries[k]) + "; expected 0.." +
                                  std::to_string(limit - 1) +
                                  " (B = " + std::to_string(config_.entry_bits) + " bits)");
    }
  }
  // Checked first, so a bad TABLE changes no bank.
  for (size_t b = 0; b < tables_.size(); ++b) {
    if (t.per_material && static_cast<int>(b) != bank_) continue;
    std::copy(t.entries.begin(), t.entries.end(),
              tables_[b].begin() + static_cast<std::ptrdiff_t>(t.base));
  }
}

int64_t ExponentLut::evaluate(int64_t series_raw) const {
  const int f = config_.interp_bits;
  // 1. ADDRESS
  const int64_t a = address_.quantize(series_raw, series_.frac_bits() - shift_ - config_.addr_bits);
  const int64_t idx = a >> f;
  // 2. READ
  const int64_t e0 = table()[static_cast<size_t>(idx)];
  if (f == 0) return out_.quantize(e0, config_.entry_bits);  // 4. OUTPUT
  const int64_t frac = a & ((int64_t{1} << f) - 1);
  const int64_t e1 = table()[static_cast<size_t>(std::min<int64_t>(idx + 1, entries() - 1))];
  // 3. INTERP
  const Int128 v = Int128{e0} * (Int128{1} << f) + Int128{frac} * (e1 - e0);
  return out_.quantize(v, config_.entry_bits + f);  // 4. OUTPUT
}

void ExponentLut::write_hex(const std::string& path) const {
  std::ofstream os(path);
  if (!os) throw std::runtime_error(path + ": cannot open for writing the LUT hex file");
  const int digits = (config_.entry_bits + 3) / 4;
  char buf[32];
  for (int64_t e : table()) {
    std::snprintf(buf, sizeof buf, "%0*llx\n", digits, static_cast<unsigned long long>(e));
    os << buf;
  }
  if (!os) throw std::runtime_error(path + ": write failed");
}

double ExponentLut::argument_scale(const LutConfig& c) {
  const double n = static_cast<double>(int64_t{1} << c.addr_bits);
  return centred(c) ? 1.0 : (n - 1.0) / n;
}

double ExponentLut::sample_argument(const LutConfig& c, int i) {
  const double n = static_cast<double>(int64_t{1} << c.addr_bits);
  return centred(c) ? (i + 0.5) / n : i / (n - 1.0);
}

}  // namespace shadesim
