#!/usr/bin/env bash
# A formal check must fail on a deliberately broken copy of the RTL (docs/formal.md):
#   broken.sh BUG WORK   BUG: queue_off_by_one | pix_handshake | pix_valid_drop
# copies rtl/ into WORK/rtl, breaks it with one sed (which must change the file), and runs the
# check of tests/formal/run.py that must catch it, requiring a failure with a VCD counterexample.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bug=$1
work=$2
case $bug in
  # span_queue reports full one entry late: a SPAN header is taken into a full ring.
  queue_off_by_one)
    file=span_queue.sv config=lut_l2_q2 catch=a_sq_no_overflow
    expr="s/full_o *= count_q == CntW'(SpanQ);/full_o = count_q == CntW'(SpanQ + 1);/" ;;
  # the pix register takes a new beat while its beat waits for pix_ready_i (no back-pressure).
  pix_handshake)
    file=out_reg.sv config=ideal_l1_q1 catch=a_pix_data_stable
    expr="s/assign adv_o = !pix_valid_o || pix_ready_i;/assign adv_o = 1'b1;/" ;;
  # pix_valid_o drops while its beat waits for pix_ready_i (the beat is lost).
  pix_valid_drop)
    file=out_reg.sv config=ideal_l1_q1 catch=a_pix_valid_held
    expr="s/else if (adv_o) pix_valid_o <= load_i;/else pix_valid_o <= load_i \&\& adv_o;/" ;;
  *) echo "broken.sh: unknown bug '$bug'" >&2; exit 2 ;;
esac
rm -rf "$work"
mkdir -p "$work"
cp -r "$root/rtl" "$work/rtl"
sed -i "$expr" "$work/rtl/$file"
if cmp -s "$root/rtl/$file" "$work/rtl/$file"; then
  echo "broken.sh: the sed changed nothing in rtl/$file (the RTL moved on): update $0" >&2
  exit 1
fi
diff "$root/rtl/$file" "$work/rtl/$file" || true
# The wrapper without the pix register's count (a_out_count), which fails first on both pix
# bugs: the port's own handshake assertion must catch them.
sed '/a_out_count: assert/d' "$here/shade_formal.sv" > "$work/shade_formal.sv"
exec python3 "$here/run.py" "$config" --mode prove --rtl "$work/rtl" --work "$work/check" \
  --wrapper "$work/shade_formal.sv" --expect-fail --expect-assert "$catch"
