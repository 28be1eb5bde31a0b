#!/usr/bin/env bash
# ctest layout_small_unit: shadesim layout on a small unit (tests/data/layout/small_unit.json:
# sphere's own unit, grey, one light, no specular unit, host setup, with 4-bit pixels and
# narrower words: 1,290 cells against sphere's 1,958, so qrouter, most of the run, takes about
# half the time), checked against what must hold of any sound layout, not against figures the
# run printed before:
#   - magic DRC 0 errors, netgen LVS clean, every routed net annotated, 0 OpenSTA SPEF warnings;
#   - a positive post-route slack at 250 MHz, and the post-route Fmax no higher than the same
#     netlist's without wires (wires only add load and delay);
#   - the die at least the cells' area, the SPEF's capacitances positive, the GDS a GDSII stream
#     (its HEADER record), the PNG a PNG of a plausible size (its IHDR), both as the JSON names.
# Usage: tests/layout_check.sh BUILD_DIR SOURCE_DIR. Exit 77 (ctest's SKIP_RETURN_CODE) when a
# tool is missing, naming its Debian package.
set -euo pipefail
build=$1
src=$2
for t in qflow:qflow graywolf:graywolf qrouter:qrouter magic:magic netgen-lvs:netgen-lvs \
  sta:opensta jq:jq python3:python3; do
  if ! command -v "${t%%:*}" >/dev/null; then
    echo "layout_small_unit: ${t%%:*} is missing (Debian package ${t#*:}; scripts/setup installs it)"
    exit 77
  fi
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
status=0
"$build/shadesim" layout --config "$src/tests/data/layout/small_unit.json" --cache "$build/area-cache" \
  --json "$out/l.json" || status=$?
[ -f "$out/l.json" ] || { echo "layout_small_unit: no JSON (exit $status)"; exit 1; }
fail() {
  echo "layout_small_unit: $*"
  exit 1
}
q() { jq -r "$1" "$out/l.json"; }
[ "$(q .drc.errors)" = 0 ] || fail "magic DRC errors: $(q .drc.errors) ($(q '.drc.kinds|join("; ")'))"
[ "$(q .lvs.clean)" = true ] || fail "LVS not clean: $(q .lvs.verdict)"
[ "$(q .annotation.unannotated_nets)" = 0 ] || fail "unannotated nets: $(q .annotation.unannotated_examples)"
[ "$(q .annotation.sta_spef_warnings)" = 0 ] || fail "OpenSTA warned on the SPEF"
[ "$status" = 0 ] || fail "shadesim layout exited $status"
python3 - "$out/l.json" <<'PY'
import json, struct, sys
j = json.load(open(sys.argv[1]))
t = j["timing"]
def check(ok, what):
    if not ok:
        sys.exit("layout_small_unit: " + what)
check(abs(j["clock_mhz"] - 250) < 1e-9, "not timed at 250 MHz: %s" % j["clock_mhz"])
check(t["worst_slack_ns"] > 0, "post-route slack %s ns at 250 MHz" % t["worst_slack_ns"])
check(t["fmax_mhz"] <= t["no_wires_fmax_mhz"] + 1e-9,
      "post-route Fmax %s above the wireless %s" % (t["fmax_mhz"], t["no_wires_fmax_mhz"]))
check(j["die"]["area_um2"] >= j["core_area_um2"] >= j["cell_area_um2"] > 0, "die < core < cells")
check(j["wire_length_um"] > 0 and j["vias"] > 0, "no wires or vias")
caps = [float(l.split()[2]) for l in open(j["files"]["spef"]) if l.startswith("*D_NET")]
check(len(caps) > 1000 and all(c >= 0 for c in caps) and sum(caps) > 0, "SPEF capacitances")
gds = open(j["files"]["gds"], "rb").read(6)
check(gds[:4] == b"\x00\x06\x00\x02", "not a GDSII stream: %r" % gds)
png = open(j["files"]["png"], "rb").read(24)
check(png[:8] == b"\x89PNG\r\n\x1a\n" and png[12:16] == b"IHDR", "not a PNG")
w, h = struct.unpack(">II", png[16:24])
check(200 <= w <= 4000 and 200 <= h <= 4000, "PNG of %d x %d" % (w, h))
print("layout_small_unit: DRC 0, LVS clean, slack %.3f ns, %.1f MHz, PNG %d x %d"
      % (t["worst_slack_ns"], t["fmax_mhz"], w, h))
PY
