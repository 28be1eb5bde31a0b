#!/bin/sh
# Both backends must produce identical results: run `shadesim cosim` on the cpp and systemc
# backends with the same configuration, scenario and seed and compare pixels, scanlines and
# cycles (and PASS).
# usage: same_results.sh SHADESIM CACHE CONFIG SCENARIO SEED
set -e
shadesim="$1"; cache="$2"; config="$3"; scenario="$4"; seed="$5"
summary() {
  "$shadesim" cosim --backend "$1" --cache "$cache" --config "$config" --scenario "$scenario" \
      --seed "$seed" --save-dir "$cache/../rtl_failures" |
    grep -E 'cycles=' | sed -E 's/.*(seed=[0-9]+) +(pixels=[0-9]+) +(scanlines=[0-9]+) +(cycles=[0-9]+).*  ([A-Z]+)$/\1 \2 \3 \4 \5/'
}
cpp=$(summary cpp)
sc=$(summary systemc)
echo "cpp:     $cpp"
echo "systemc: $sc"
[ -n "$cpp" ] && [ "$cpp" = "$sc" ] || { echo "same_results: the backends disagree" >&2; exit 1; }
case "$cpp" in *PASS) ;; *) echo "same_results: runs did not pass" >&2; exit 1 ;; esac
