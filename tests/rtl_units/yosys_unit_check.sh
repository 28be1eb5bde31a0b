#!/bin/sh
# Synthesize specular_unit (with one unit selected by chparam) and fail if a latch was inferred.
# usage: yosys_unit_check.sh YOSYS LOG "CHPARAM-ARGS" rtl/*.sv
set -e
yosys="$1"; log="$2"; params="$3"; shift 3
"$yosys" -q -l "$log" -p "read_verilog -sv $*; chparam $params specular_unit; synth -top specular_unit; stat" >/dev/null
if grep -E 'Latch inferred|\$dlatch|\$_DLATCH' "$log"; then
  echo "yosys_unit_check: latch inferred (see $log)" >&2
  exit 1
fi
cells=$(sed -n '/=== design hierarchy ===/,$p' "$log" | grep -m1 'Number of cells' | tr -s ' ')
[ -n "$cells" ] || { echo "yosys_unit_check: no design hierarchy statistics (see $log)" >&2; exit 1; }
echo "yosys_unit_check: no latches; $params;$cells"
