#!/usr/bin/env bash
# Scaling of one render over devices and MPI ranks at equal total threads, on
# one machine: PoCL shows its CPU as one device of T threads or as several
# devices of fewer threads (POCL_DEVICES, POCL_MAX_PTHREAD_COUNT), and mpirun
# runs ranks side by side. Median of three runs each; then the paper estimate
# of the communication a frame needs over a network (comm_estimate.py).
#   benchmarks/scale_out/run.sh BUILD_DIR OUT_DIR [SPP] [WIDTH] [HEIGHT]
set -euo pipefail
build=${1:?build folder}
out=${2:?output folder}
spp=${3:-128}
width=${4:-256}
height=${5:-192}
clpath=$build/clpath
here=$(cd "$(dirname "$0")" && pwd)
threads=$(nproc)
mkdir -p "$out"
log=$out/log.txt
: >"$log"
base=(render --width "$width" --height "$height" --seed 1 -q -o "$out/image.pfm")
args=("${base[@]}" --spp "$spp")
mpirun_cmd=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpirun_cmd+=(--allow-run-as-root)

# One configuration: prints its median Msamples/s over three runs.
measure() {
    local name=$1
    shift
    local rates=()
    for run in 1 2 3; do
        local line
        line=$("$@" 2>>"$log" | grep '^summary:')
        echo "$name run $run: $line" >>"$log"
        rates+=("$(sed -E 's/.*msamples_per_s=([0-9.]+).*/\1/' <<<"$line")")
    done
    printf '%s\n' "${rates[@]}" | sort -g | sed -n 2p
}

# Warm the kernel cache so no configuration pays a compile.
"$clpath" "${base[@]}" --spp 1 >/dev/null 2>&1

one_thread=$(measure "1 device x 1 thread" env POCL_MAX_PTHREAD_COUNT=1 "$clpath" "${args[@]}")
one_device=$(measure "1 device x $threads threads" env POCL_MAX_PTHREAD_COUNT="$threads" "$clpath" "${args[@]}")
# PoCL's pthread devices in one process share one pool of worker threads
# (POCL_MAX_PTHREAD_COUNT is its size, not each device's): N devices of one
# thread each would share a single thread. Equal total threads is N devices
# over a pool of N.
devices=$(measure "$threads devices sharing $threads threads" env POCL_DEVICES="$(printf 'pthread %.0s' $(seq "$threads"))" \
    POCL_MAX_PTHREAD_COUNT="$threads" "$clpath" "${args[@]}" --device all)
ranks=$(measure "$threads ranks x 1 device x 1 thread" "${mpirun_cmd[@]}" -n "$threads" \
    -x POCL_MAX_PTHREAD_COUNT=1 -x CLPATH_CACHE_DIR "$clpath" "${args[@]}")

device=$("$clpath" devices | grep -m1 '\[0\]' | sed 's/^ *//')
commit=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)
{
    echo "# Scale-out: one render over devices and MPI ranks"
    echo
    echo "- device: \`$device\`; PoCL splits its $threads CPU threads into devices or ranks"
    echo "- date: $(date -u +%Y-%m-%dT%H:%M:%SZ); commit: $commit; host: $(hostname), $threads cores"
    echo "- \`clpath render\` of the default scene, ${width}x${height}, $spp spp, median of three runs;"
    echo "  Msamples/s from each run's summary line (render time from the first chunk: compiles left out)"
    echo "- every configuration renders the same image, bit for bit (tests/cli/scale_out_tests.cmake checks it)"
    echo
    echo "| configuration | threads in all | Msamples/s | speed-up over 1 thread | efficiency |"
    echo "|---|--:|--:|--:|--:|"
    for row in "1 device x 1 thread|1|$one_thread" "1 device x $threads threads|$threads|$one_device" \
               "$threads devices sharing PoCL's $threads threads|$threads|$devices" "$threads MPI ranks x 1 device x 1 thread|$threads|$ranks"; do
        IFS='|' read -r name n rate <<<"$row"
        awk -v name="$name" -v n="$n" -v r="$rate" -v base="$one_thread" \
            'BEGIN { printf "| %s | %d | %.3f | %.2f | %.0f %% |\n", name, n, r, r / base, 100 * r / base / n }'
    done
    echo
    python3 "$here/comm_estimate.py"
} >"$out/README.md"
rm -f "$out/image.pfm"
cat "$out/README.md"
