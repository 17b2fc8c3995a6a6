#!/usr/bin/env bash
# Ctrl-C during a render keeps the whole chunks done so far and exits 130
# (SIGTERM: 143), as shells report a death by those signals; a checkpoint
# taken before it, resumed, gives the same bits as the render never
# interrupted, says where it resumed, counts only its own samples in its
# rates, and is removed once the render finishes (unless --keep-checkpoint).
#   interrupt_resume.sh CLPATH OUT_DIR
set -euo pipefail
clpath=$1
out=$2
mkdir -p "$out"
rm -f "$out"/ir_* "$out"/ir.ckpt "$out"/ir_*.ckpt
# Long enough (128 chunks, about 2 s on two cores) that the render is still
# running when the script has seen its first checkpoint and signals it.
loud=(render --spp 512 --chunk 4 --width 48 --height 40 --seed 5)
args=("${loud[@]}" -q)

# Waits until FILE exists or PID has ended; fails if FILE never came.
wait_for_file() {
    local file=$1 pid=$2 log=$3
    for _ in $(seq 600); do
        [ -f "$file" ] && return 0
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
    done
    [ -f "$file" ] || { cat "$log"; echo "no checkpoint was written"; exit 1; }
}

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
cp "$out/ir_saved.ckpt" "$out/ir_kept.ckpt"
kill -INT $pid || true
rc=0
wait $pid || rc=$?
cat "$out/ir_partial.log"
if grep -q "interrupted=1" "$out/ir_partial.log"; then
    [ $rc -eq 130 ] || { echo "a render interrupted by SIGINT exited $rc, not 130"; exit 1; }
    [ -f "$out/ir_partial.pfm" ] || { echo "the interrupted render wrote no image"; exit 1; }
    grep -q "interrupted by signal 2" "$out/ir_partial.log"
    [ -f "$out/ir.ckpt" ] || { echo "the interrupted render removed its checkpoint"; exit 1; }
else
    [ $rc -eq 0 ] || { echo "the render finished before the signal but exited $rc"; exit 1; }
    [ ! -e "$out/ir.ckpt" ] || { echo "the finished render left its checkpoint"; exit 1; }
fi

# Resumed: the same bits, "resumed at N spp", rates over this run's samples, the checkpoint consumed.
saved_spp=$("$clpath" "${loud[@]}" --resume "$out/ir_saved.ckpt" -o "$out/ir_resumed.pfm" 2>&1 | tee "$out/ir_resumed.log" |
    sed -n 's/^clpath: resumed at \([0-9]*\) spp from .*ir_saved\.ckpt$/\1/p')
cat "$out/ir_resumed.log"
[ -n "$saved_spp" ] && [ "$saved_spp" -gt 0 ] && [ "$saved_spp" -lt 512 ] ||
    { echo "no 'resumed at N spp' line (or N not in 1..511)"; exit 1; }
cmp "$out/ir_reference.pfm" "$out/ir_resumed.pfm"
echo "resumed render identical to the uninterrupted one"
grep -q "spp=512 .* resumed_spp=$saved_spp" "$out/ir_resumed.log" || { echo "the summary does not name resumed_spp=$saved_spp"; exit 1; }
# msamples_per_s = (512 - resumed) * 48 * 40 / render_s / 1e6, to the printed precision.
awk -v resumed="$saved_spp" '/^summary:/ {
        for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
        want = (512 - resumed) * 48 * 40 / v["render_s"] / 1e6
        # render_s is printed to 1 ms: the rate is known to within that relative error, plus rounding.
        tol = want * 0.0005 / v["render_s"] + 0.0006
        if (v["msamples_per_s"] < want - tol || v["msamples_per_s"] > want + tol) {
            printf "msamples_per_s=%s, but this run rendered %d spp in %s s: %.3f\n", v["msamples_per_s"], 512 - resumed, v["render_s"], want
            exit 1
        }
        found = 1
    } END { exit found ? 0 : 1 }' "$out/ir_resumed.log"
[ ! -e "$out/ir_saved.ckpt" ] || { echo "the resumed checkpoint was not removed after the render finished"; exit 1; }
grep -q "removed the checkpoint .*ir_saved.ckpt" "$out/ir_resumed.log"
# --keep-checkpoint keeps it (the control for the removal above).
"$clpath" "${args[@]}" --resume "$out/ir_kept.ckpt" --keep-checkpoint -o "$out/ir_kept.pfm"
[ -f "$out/ir_kept.ckpt" ] || { echo "--keep-checkpoint did not keep the checkpoint"; exit 1; }
cmp "$out/ir_reference.pfm" "$out/ir_kept.pfm"
echo "checkpoints removed after a finished render, kept with --keep-checkpoint"

# A damaged or forged checkpoint is refused with its own message, exit 1, nothing written.
resume_fails() {
    local ckpt=$1 want=$2 rc=0
    "$clpath" "${args[@]}" --resume "$ckpt" -o "$out/ir_bad.pfm" >"$out/ir_bad.log" 2>&1 || rc=$?
    cat "$out/ir_bad.log"
    [ $rc -eq 1 ] || { echo "resuming $ckpt exited $rc, not 1"; exit 1; }
    grep -q "^clpath: error: $ckpt: $want" "$out/ir_bad.log" || { echo "no '$want' for $ckpt"; exit 1; }
    [ ! -e "$out/ir_bad.pfm" ] || { echo "resuming $ckpt wrote an image"; exit 1; }
}
cp "$out/ir_kept.ckpt" "$out/ir_flipped.ckpt"
size=$(stat -c %s "$out/ir_flipped.ckpt")
printf '\x55' | dd of="$out/ir_flipped.ckpt" bs=1 seek=$((size - 100)) conv=notrunc 2>/dev/null  # a byte of the sums
resume_fails "$out/ir_flipped.ckpt" "the checkpoint is damaged: its xxHash checksum does not match its contents"
cp "$out/ir_kept.ckpt" "$out/ir_forged.ckpt"
printf '\x00\x40\x00\x00\x00\x00\x00\x00' | dd of="$out/ir_forged.ckpt" bs=1 seek=40 conv=notrunc 2>/dev/null  # width 16384
resume_fails "$out/ir_forged.ckpt" "the checkpoint's header describes [0-9]* bytes, but the file has $size"
echo "damaged and forged checkpoints refused"

# SIGTERM: the partial image is written, exit 143.
rm -f "$out/ir_term.ckpt"
"$clpath" render --spp 100000 --width 32 --height 24 --checkpoint 0.05 --checkpoint-file "$out/ir_term.ckpt" \
    -o "$out/ir_term.pfm" >"$out/ir_term.log" 2>&1 &
pid=$!
wait_for_file "$out/ir_term.ckpt" $pid "$out/ir_term.log"
kill -TERM $pid
rc=0
wait $pid || rc=$?
cat "$out/ir_term.log"
[ $rc -eq 143 ] || { echo "a render stopped by SIGTERM exited $rc, not 143"; exit 1; }
[ -f "$out/ir_term.pfm" ] || { echo "the render stopped by SIGTERM wrote no image"; exit 1; }
grep -q "interrupted by signal 15" "$out/ir_term.log"
grep -q "wrote .*ir_term.pfm" "$out/ir_term.log"
echo "SIGTERM: partial image written, exit 143"

# --no-partial: interrupted, nothing written, exit 143 all the same.
rm -f "$out/ir_none.ckpt"
"$clpath" render --spp 100000 --width 64 --height 64 --no-partial --checkpoint 0.05 --checkpoint-file "$out/ir_none.ckpt" \
    -o "$out/ir_none.pfm" >"$out/ir_none.log" 2>&1 &
pid=$!
wait_for_file "$out/ir_none.ckpt" $pid "$out/ir_none.log"
kill -TERM $pid
rc=0
wait $pid || rc=$?
cat "$out/ir_none.log"
[ $rc -eq 143 ] || { echo "--no-partial after SIGTERM exited $rc, not 143"; exit 1; }
[ ! -e "$out/ir_none.pfm" ] || { echo "--no-partial wrote an image"; exit 1; }
echo "--no-partial wrote nothing"
