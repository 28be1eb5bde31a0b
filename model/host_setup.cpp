#include "model/host_setup.h"

#include <utility>
#include <variant>

#include "model/span_setup.h"
#include "model/start_packing.h"

namespace shadesim {

CommandStream with_host_setup(const CommandStream& unit_stream) {
  CommandStream out;
  out.config = unit_stream.config;
  out.config.span_setup = SpanSetupSite::kHost;
  const UnitConfig& c = unit_stream.config;
  const SpanSetup setup(c.coef, c.series, c.offset_bits);
  const int series = c.series_per_triangle();
  const TriangleCmd* tri = nullptr;
  out.commands.reserve(unit_stream.commands.size());
  for (const Command& cmd : unit_stream.commands) {
    if (const auto* t = std::get_if<TriangleCmd>(&cmd)) {
      tri = t;
      continue;
    }
    if (const auto* s = std::get_if<SpanCmd>(&cmd)) {
      if (tri == nullptr) throw CommandStreamError("host setup: span before any tri command");
      SpanCmd span = *s;
      span.starts.clear();
      span.starts.reserve(static_cast<size_t>(StartLayout::kValuesPerSeries * series));
      for (int i = 0; i < series; ++i) {
        const SeriesStart st = setup(&tri->coef[static_cast<size_t>(i) * kTermsPerSeries],
                                     s->x0 - tri->xo, s->y - tri->yo);
        span.starts.insert(span.starts.end(), {st.v, st.d, st.d2});
      }
      out.commands.emplace_back(std::move(span));
      continue;
    }
    out.commands.push_back(cmd);
  }
  return out;
}

}  // namespace shadesim
