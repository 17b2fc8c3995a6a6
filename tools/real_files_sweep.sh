#!/usr/bin/env bash
# Renders every OBJ, glTF and GLB file of two Debian packages as a new user
# would (clpath render FILE) and records, per file: exit status, the first
# error or warning, wall time, and how much of the image the model covers.
#
#   tools/real_files_sweep.sh [CLPATH] [OUT_DIR] [FILE...]
#
# Without FILEs: every model file of the two packages below.
#
# Needs glmark2-data and assimp-testmodels (apt-get install assimp-testmodels)
# and python3-numpy. Light on purpose (160x120, 4 spp): the machine is shared.
#
# Coverage: a second render with the albedo integrator, no ground and a black
# environment, so every pixel that is not black hit the model. A model seen
# edge-on or missed by the camera shows as a coverage near 0.
set -uo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
clpath=${1:-$here/build/clpath}
out=${2:-/tmp/sweep}
limit=${SWEEP_TIMEOUT:-120}  # seconds; past it a render counts as a hang
mkdir -p "$out"
python=/usr/bin/python3  # Debian's, with python3-numpy

shift $(( $# < 2 ? $# : 2 ))
if [ $# -gt 0 ]; then
    files=("$@")
else
    mapfile -t files < <( { find /usr/share/glmark2/models /usr/share/assimp/models -type f \
        \( -iname '*.obj' -o -iname '*.gltf' -o -iname '*.glb' \) 2>/dev/null; } | sort)
fi
[ ${#files[@]} -gt 0 ] || { echo "no model files: apt-get install glmark2-data assimp-testmodels" >&2; exit 1; }

table=$out/results.tsv
printf 'file\trc\tseconds\tcoverage\tmessage\n' >"$table"
for f in "${files[@]}"; do
    name=$(echo "${f#/usr/share/}" | tr '/ ' '__')
    log=$out/$name.log
    t0=$(date +%s%N)
    timeout -s INT "$limit" "$clpath" render "$f" --spp 4 --width 160 --height 120 -o "$out/$name.png" >"$log" 2>&1
    rc=$?
    t1=$(date +%s%N)
    ms=$(( (t1 - t0) / 1000000 ))
    # The first error, else the first warning, else nothing: what a user reads first.
    msg=$(grep -m1 'clpath: error:' "$log" || grep -m1 -i 'warning' "$log" || true)
    msg=${msg//$'\t'/ }
    cov=-
    if [ $rc -eq 0 ]; then
        if "$clpath" render "$f" -i albedo --no-ground --env 0 --spp 1 --width 80 --height 60 -q \
            -o "$out/$name.cov.pfm" >"$out/$name.cov.log" 2>&1; then
            cov=$("$python" - "$out/$name.cov.pfm" <<'EOF'
import sys
import numpy as np
with open(sys.argv[1], 'rb') as f:
    assert f.readline().strip() == b'PF'
    w, h = map(int, f.readline().split())
    scale = float(f.readline())
    px = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4').reshape(h, w, 3)
print(f"{(px.max(axis=2) > 0).mean():.3f}")
EOF
)
        else
            cov=failed
        fi
    fi
    printf '%s\t%s\t%d.%d\t%s\t%s\n' "$f" "$rc" $((ms / 1000)) $((ms % 1000 / 100)) "$cov" "$msg" | tee -a "$table"
done
echo "wrote $table"

"$python" "$here/tools/real_files_summary.py" "$table" >"$out/summary.md"
echo "wrote $out/summary.md"
