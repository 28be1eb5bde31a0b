#!/bin/sh
# Both backends must produce identical results: run rtl_cosim_cpp and rtl_cosim_sc on the same
# configuration, scenario and seed and compare pixels, scanlines and cycles (and PASS).
# usage: same_results.sh BUILD_DIR CONFIG SCENARIO SEED
set -e
build="$1"; config="$2"; scenario="$3"; seed="$4"
summary() {
  "$build/$1" --config "$config" --scenario "$scenario" --seed "$seed" --save-dir "$build/rtl_failures" |
    grep -E 'cycles=' | sed -E 's/.*(seed=[0-9]+) +(pixels=[0-9]+) +(scanlines=[0-9]+) +(cycles=[0-9]+).*  ([A-Z]+)$/\1 \2 \3 \4 \5/'
}
cpp=$(summary rtl_cosim_cpp)
sc=$(summary rtl_cosim_sc)
echo "cpp:     $cpp"
echo "systemc: $sc"
[ -n "$cpp" ] && [ "$cpp" = "$sc" ] || { echo "same_results: the backends disagree" >&2; exit 1; }
case "$cpp" in *PASS) ;; *) echo "same_results: runs did not pass" >&2; exit 1 ;; esac
