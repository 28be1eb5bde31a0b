#include "model/host_setup.h"

#include <optional>
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
      span.starts.reserve(static_cast<size_t>(StartLayout::kValuesPerSeries) * series);
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

CommandStream with_host_setup(CommandStream&& unit_stream) {
  CommandStream out = std::move(unit_stream);
  const UnitConfig c = out.config;
  out.config.span_setup = SpanSetupSite::kHost;
  const SpanSetup setup(c.coef, c.series, c.offset_bits);
  const int series = c.series_per_triangle();
  // Commands move down over the TRIANGLEs they drop (write <= read), so the triangle a span
  // needs is kept aside: its slot may be overwritten before the triangle's last span is read.
  std::optional<TriangleCmd> tri;
  size_t write = 0;
  for (size_t read = 0; read < out.commands.size(); ++read) {
    Command& cmd = out.commands[read];
    if (auto* t = std::get_if<TriangleCmd>(&cmd)) {
      tri = std::move(*t);
      continue;
    }
    if (auto* s = std::get_if<SpanCmd>(&cmd)) {
      if (!tri) throw CommandStreamError("host setup: span before any tri command");
      s->starts.clear();
      s->starts.reserve(static_cast<size_t>(StartLayout::kValuesPerSeries) * series);
      for (int i = 0; i < series; ++i) {
        const SeriesStart st = setup(&tri->coef[static_cast<size_t>(i) * kTermsPerSeries],
                                     s->x0 - tri->xo, s->y - tri->yo);
        s->starts.insert(s->starts.end(), {st.v, st.d, st.d2});
      }
    }
    if (write != read) out.commands[write] = std::move(cmd);
    ++write;
  }
  out.commands.resize(write);  // no shrink_to_fit: it would copy every command once more
  return out;
}

}  // namespace shadesim
