// Host span setup (UnitConfig::span_setup kHost): the host does the unit's span setup itself and
// sends each span's start values after its SPAN header instead of the triangle's coefficients.
#pragma once

#include "model/command_stream.h"

namespace shadesim {

// The same frame for a host-setup unit: `unit_stream` (a unit-setup stream for the same widths)
// without its TRIANGLE commands, every SPAN carrying v, d, d2 of each series as the unit's span
// setup would form them - the model's own SpanSetup on the triangle's coefficients and the span's
// offsets from its origin - so every pixel is the unit-setup stream's, bit for bit. The result's
// config is unit_stream's with span_setup kHost.
CommandStream with_host_setup(const CommandStream& unit_stream);
// The same, converting `unit_stream` in place: a large frame never holds both streams.
CommandStream with_host_setup(CommandStream&& unit_stream);

}  // namespace shadesim
