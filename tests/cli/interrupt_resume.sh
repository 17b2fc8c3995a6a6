#!/usr/bin/env bash
# Ctrl-C during a render keeps the whole chunks done so far; a checkpoint taken
# before it, resumed, gives the same bits as the render never interrupted.
#   interrupt_resume.sh CLPATH OUT_DIR
set -euo pipefail
clpath=$1
out=$2
mkdir -p "$out"
rm -f "$out"/ir_* "$out"/ir.ckpt
# Long enough (128 chunks, about 2 s on two cores) that the render is still
# running when the script has seen its first checkpoint and signals it.
args=(render --spp 512 --chunk 4 --width 48 --height 40 --seed 5 -q)

# The reference: the same render, uninterrupted.
"$clpath" "${args[@]}" -o "$out/ir_reference.pfm"

# Interrupted once a checkpoint exists, then resumed.
"$clpath" "${args[@]}" --checkpoint 0.05 --checkpoint-file "$out/ir.ckpt" -o "$out/ir_partial.pfm" \
    >"$out/ir_partial.log" 2>&1 &
pid=$!
# The copy is taken at once: the render may finish and remove its own before
# the signal lands. (A checkpoint is replaced whole, by a rename: a copy is
# never half of one.)
for _ in $(seq 1800); do
    cp "$out/ir.ckpt" "$out/ir_saved.ckpt" 2>/dev/null && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
done
[ -f "$out/ir_saved.ckpt" ] || { cat "$out/ir_partial.log"; echo "no checkpoint was seen while the render ran"; exit 1; }
kill -INT $pid || true
rc=0
wait $pid || rc=$?
cat "$out/ir_partial.log"
[ $rc -eq 0 ] || { echo "interrupted render exited $rc"; exit 1; }
if grep -q "interrupted=1" "$out/ir_partial.log"; then
    [ -f "$out/ir_partial.pfm" ] || { echo "the interrupted render wrote no image"; exit 1; }
    grep -q "interrupted by signal 2" "$out/ir_partial.log"
fi
"$clpath" "${args[@]}" --resume "$out/ir_saved.ckpt" -o "$out/ir_resumed.pfm"
cmp "$out/ir_reference.pfm" "$out/ir_resumed.pfm"
echo "resumed render identical to the uninterrupted one"

# --no-partial: interrupted, nothing written.
"$clpath" render --spp 100000 --width 64 --height 64 -q --no-partial -o "$out/ir_none.pfm" >"$out/ir_none.log" 2>&1 &
pid=$!
sleep 2
kill -TERM $pid
rc=0
wait $pid || rc=$?
cat "$out/ir_none.log"
[ $rc -ne 0 ] || { echo "--no-partial after SIGTERM must exit non-zero"; exit 1; }
[ ! -e "$out/ir_none.pfm" ] || { echo "--no-partial wrote an image"; exit 1; }
echo "--no-partial wrote nothing"
