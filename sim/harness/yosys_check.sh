#!/bin/sh
# Synthesize shade_unit with Yosys and fail if any latch was inferred.
# usage: yosys_check.sh YOSYS LOG rtl/*.sv
# YOSYS_CHPARAM (optional): chparam arguments for shade_unit, e.g. "-set SPECULAR_KIND 3".
set -e
yosys="$1"; log="$2"; shift 2
chparam=""
[ -n "$YOSYS_CHPARAM" ] && chparam="chparam $YOSYS_CHPARAM shade_unit;"
"$yosys" -q -l "$log" -p "read_verilog -sv $*; $chparam synth -top shade_unit; stat" >/dev/null
if grep -E 'Latch inferred|\$dlatch|\$_DLATCH' "$log"; then
  echo "yosys_check: latch inferred (see $log)" >&2
  exit 1
fi
grep -q 'Number of cells' "$log" || { echo "yosys_check: synth produced no statistics (see $log)" >&2; exit 1; }
echo "yosys_check: no latches; $(grep -m1 'Number of cells' "$log" | tr -s ' ')"
