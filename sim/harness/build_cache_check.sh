#!/bin/sh
# The on-demand RTL build cache (sim/eda/verilator/rtl_build.h), on a small private cache:
#   1. two concurrent builds of one key both succeed and name the same executable;
#   2. the next run reuses it (cached, no Verilator);
#   3. a changed parameter is a new key (a build);
#   4. a changed RTL source is a new key: a copy of rtl/ (SHADESIM_RTL_DIR) gives the same key
#      as the checkout, and the copy with one line added gives another (the checkout is never
#      edited);
#   5. a changed model or harness library (SHADESIM_HARNESS_LIB_DIR: a copy with one object
#      added) keeps every build key, relinks every cached build and Verilates or compiles none;
#   6. a fast build leaves the RTL's SVA out and a quick one keeps them (checks_assertions,
#      sim/eda/verilator/rtl_recipe.h): two keys, and only the quick model's Verilator command has --assert.
# usage: build_cache_check.sh SHADESIM WORKDIR
set -eu
shadesim="$1"; work="$2"
rm -rf "$work"; mkdir -p "$work"
cache="$work/cache"
cat >"$work/small.json" <<'JSON'
{"channels": 1, "lights": 1, "xy_bits": 8, "coef": "s3.20:rnd:sat", "series": "s3.16",
 "spec_colour": "u1.8:rnd:sat", "out_bits": 8, "specular": {"kind": "ideal", "out": "u1.10:sat"}}
JSON
sed 's/"xy_bits": 8/"xy_bits": 9/' "$work/small.json" >"$work/small9.json"

# 1. Two processes, one key, at once.
"$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" >"$work/a.out" 2>"$work/a.err" &
a=$!
"$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" >"$work/b.out" 2>"$work/b.err" &
b=$!
wait $a || { echo "first concurrent build failed:"; cat "$work/a.err"; exit 1; }
wait $b || { echo "second concurrent build failed:"; cat "$work/b.err"; exit 1; }
exe_a=$(awk '{print $3}' "$work/a.out"); exe_b=$(awk '{print $3}' "$work/b.out")
[ "$exe_a" = "$exe_b" ] || { echo "concurrent builds name different executables: $exe_a vs $exe_b"; exit 1; }
[ -x "$exe_a" ] || { echo "no executable at $exe_a"; exit 1; }
builds=$(cat "$work/a.err" "$work/b.err" | grep -c 'built in' || true)
[ "$builds" -eq 1 ] || { echo "expected exactly one of the two to build, got $builds"; cat "$work"/*.err; exit 1; }
[ "$(ls -d "$cache"/cpp-* | grep -Evc '\.(lock|log)$')" -eq 1 ] || { echo "cache holds more than one build"; ls "$cache"; exit 1; }
ls "$cache" | grep -q '\.tmp\.' && { echo "a temporary build folder was left behind"; ls "$cache"; exit 1; }
"$exe_a" --unit "$work/small.json" --scenario short --seed 1 | grep -q PASS ||
  { echo "the built executable does not pass"; exit 1; }

# 2. Reuse.
"$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" >"$work/c.out" 2>"$work/c.err"
grep -q '(cached)' "$work/c.out" || { echo "second run did not reuse the build:"; cat "$work/c.out" "$work/c.err"; exit 1; }
grep -q 'Verilating' "$work/c.err" && { echo "second run Verilated again"; exit 1; }

# 3. A changed parameter.
"$shadesim" rtl-build --config "$work/small9.json" --backends cpp --cache "$cache" >"$work/d.out" 2>"$work/d.err"
grep -q '(cached)' "$work/d.out" && { echo "a changed parameter reused the old build"; exit 1; }
[ "$(awk '{print $3}' "$work/d.out")" != "$exe_a" ] || { echo "a changed parameter gave the same executable"; exit 1; }

# 4. A changed RTL source: a copy of the checkout with one comment added to an RTL file.
src=$("$shadesim" rtl-build --print-source-dir)
cp -r "$src/rtl" "$work/rtl-copy"
key1=$(SHADESIM_RTL_DIR="$work/rtl-copy" "$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --print-key)
echo "// changed" >>"$work/rtl-copy/series_engine.sv"
key2=$(SHADESIM_RTL_DIR="$work/rtl-copy" "$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --print-key)
key0=$("$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --print-key)
[ "$key1" = "$key0" ] || { echo "an identical copy of the RTL gave another key"; exit 1; }
[ "$key1" != "$key2" ] || { echo "a changed RTL source kept the key"; exit 1; }
echo "build cache: concurrent builds agree, reuse, parameter and source changes rebuild"

# 5. A changed model or harness library relinks every cached build and Verilates none. The
# libraries are copied and the model's gains one object, as any edit of a model source changes
# libshadesim_model.a; the checkout's own libraries are not touched.
libs="$work/libs"
mkdir -p "$libs"
bin=$(dirname "$(command -v "$shadesim" || echo "$shadesim")")
cp "$bin/libshadesim_harness.a" "$bin/libshadesim_model.a" "$libs/"
echo 'int shadesim_model_edit_marker = 1;' >"$work/marker.cpp"
g++ -c -o "$work/marker.o" "$work/marker.cpp"
ar rs "$libs/libshadesim_model.a" "$work/marker.o" 2>/dev/null
keys_before=$("$shadesim" rtl-build --config "$work/small.json,$work/small9.json" --backends cpp --cache "$cache" --print-key)
keys_after=$(SHADESIM_HARNESS_LIB_DIR="$libs" "$shadesim" rtl-build --config "$work/small.json,$work/small9.json" --backends cpp --cache "$cache" --print-key)
[ "$keys_before" = "$keys_after" ] || { echo "a changed library changed the build keys (the Verilated model's)"; exit 1; }
SHADESIM_HARNESS_LIB_DIR="$libs" "$shadesim" rtl-build --config "$work/small.json,$work/small9.json" --backends cpp --cache "$cache" >"$work/e.out" 2>"$work/e.err"
[ "$(grep -c '(relinked)' "$work/e.out")" -eq 2 ] || { echo "expected both cached builds relinked:"; cat "$work/e.out" "$work/e.err"; exit 1; }
grep -Eq 'Verilating|compiling' "$work/e.err" && { echo "a changed library Verilated or compiled a model again:"; cat "$work/e.err"; exit 1; }
exe_e=$(awk '$1 == "'"$work/small.json"'" {print $3}' "$work/e.out")
[ "$exe_e" != "$exe_a" ] || { echo "the relinked executable has the old name"; exit 1; }
"$exe_e" --unit "$work/small.json" --scenario short --seed 1 | grep -q PASS ||
  { echo "the relinked executable does not pass"; exit 1; }
echo "build cache: a changed model library relinks every cached build without Verilating"

# 6. Fast without the SVA, quick with them: read from the Verilator command each build logged.
key_fast=$("$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --opt fast --print-key)
key_quick=$("$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --opt quick --print-key)
[ "$key_fast" != "$key_quick" ] || { echo "fast and quick builds share a model key ($key_fast)"; exit 1; }
"$shadesim" rtl-build --config "$work/small.json" --backends cpp --cache "$cache" --opt quick >"$work/f.out" 2>"$work/f.err" ||
  { echo "the quick build failed:"; cat "$work/f.err"; exit 1; }
verilator_line() { grep -m1 -- ' --top-module shade_unit ' "$cache/cpp-$1.log"; }
verilator_line "$key_quick" | grep -q -- ' --assert' ||
  { echo "the quick build was Verilated without --assert:"; verilator_line "$key_quick"; exit 1; }
[ -n "$(verilator_line "$key_fast")" ] || { echo "no Verilator command in cpp-$key_fast.log"; exit 1; }
verilator_line "$key_fast" | grep -q -- ' --assert' &&
  { echo "the fast build was Verilated with --assert:"; verilator_line "$key_fast"; exit 1; }
"$(awk '{print $3}' "$work/f.out")" --unit "$work/small.json" --scenario short --seed 1 | grep -q PASS ||
  { echo "the quick executable does not pass"; exit 1; }
echo "build cache: fast builds leave the SVA out, quick builds keep them"
