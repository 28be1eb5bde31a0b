#!/bin/sh
# Synthesize shade_unit with Yosys and fail if any latch was inferred.
# usage: yosys_check.sh YOSYS LOG rtl/*.sv
# YOSYS_CHPARAM (optional): chparam arguments for shade_unit, e.g. "-set SPECULAR_KIND 3".
# YOSYS_LATCH_ONLY=1 (optional): elaborate and run `proc` instead of a full `synth`. Latches are
# inferred by `proc` (proc_dlatch), so this finds every one in a fraction of synth's time; the
# parameter variants use it, the default build runs the full synth.
set -e
yosys="$1"; log="$2"; shift 2
chparam=""
[ -n "$YOSYS_CHPARAM" ] && chparam="chparam $YOSYS_CHPARAM shade_unit;"
passes="synth -top shade_unit"
[ "${YOSYS_LATCH_ONLY:-0}" = 1 ] && passes="hierarchy -check -top shade_unit; proc"
"$yosys" -q -l "$log" -p "read_verilog -sv $*; $chparam $passes; stat" >/dev/null
if grep -E 'Latch inferred|\$dlatch|\$_DLATCH' "$log"; then
  echo "yosys_check: latch inferred (see $log)" >&2
  exit 1
fi
grep -q 'Number of cells' "$log" || { echo "yosys_check: synth produced no statistics (see $log)" >&2; exit 1; }
echo "yosys_check: no latches ($passes); $(grep -m1 'Number of cells' "$log" | tr -s ' ')"
