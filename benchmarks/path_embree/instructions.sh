#!/usr/bin/env bash
# Instructions per ray, counted by callgrind (deterministic, unlike this
# machine's wall time, which moves by a quarter between processes): Embree's
# `pathtracer` example against clpath's built-in Embree path tracer
# (host/bench/embree_path_tracer.cpp, default mode and robust) on the scene
# pathtracer.sh times, one thread each, split into Embree's traversal
# (everything under rtcIntersect1 / rtcOccluded1) and the rest (camera,
# shading, light sampling, film): the comparison of the two path tracers'
# own code per ray that the wall-time rounds are too noisy to settle.
# clpath's kernels are counted too (its traversal and the rest of its
# megakernel), though callgrind runs them as PoCL's haswell code.
#   benchmarks/path_embree/instructions.sh [RESULT_DIR_NAME] [BUILD_DIR]
# writes benchmarks/results/RESULT_DIR_NAME/path-embree-pathtracer/instructions.md
# Environment: SPP (4), DEPTH (4), SIZE (128), SCENE (scenes/cornell-point.json), PATHTRACER.
# Needs valgrind (tools/install-deps.sh). About 8 minutes on a 2-core Xeon.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
DEV_DIR=${1:-pocl-xeon-2core}
B=${2:-$ROOT/build}
CLPATH=$B/clpath
SPP=${SPP:-4}
DEPTH=${DEPTH:-4}
SIZE=${SIZE:-128}
SCENE=${SCENE:-$ROOT/scenes/cornell-point.json}
PATHTRACER=${PATHTRACER:-$(command -v pathtracer || true)}
OUT=$ROOT/benchmarks/results/$DEV_DIR/path-embree-pathtracer
[ -x "$CLPATH" ] || { echo "instructions.sh: error: $CLPATH: no clpath build there" >&2; exit 1; }
[ -n "$PATHTRACER" ] && [ -x "$PATHTRACER" ] ||
  { echo "instructions.sh: error: Embree's pathtracer not found (Debian: apt-get install embree-tools)" >&2; exit 1; }
command -v valgrind > /dev/null || { echo "instructions.sh: error: valgrind not found (tools/install-deps.sh)" >&2; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$OUT"
CG=(valgrind --tool=callgrind --compress-strings=no --compress-pos=no)
"$CLPATH" export "$SCENE" "$WORK/scene.ecs" --format embree --max-depth "$DEPTH" --width "$SIZE" --height "$SIZE" >&2

# The example renders a warm-up frame and timed ones; one frame's count is
# the difference between a run of two frames and a run of one.
for frames in "0 1" "1 1"; do
  (cd "$WORK" && "${CG[@]}" --callgrind-out-file="pt-${frames/ /-}.cg" "$PATHTRACER" -c scene.ecs --spp "$SPP" \
    --threads 1 --benchmark $frames --legacy) > "$WORK/pt-${frames/ /-}.log" 2>&1
done
# bench path renders with clpath, then the built-in tracer in default mode and
# robust, a warm-up launch of each first: a dump at each entry to and exit
# from the tracer's render makes the even parts its four renders, in order.
RENDER='clpath::(anonymous namespace)::Tracer::render(unsigned int, unsigned int)'
(cd "$WORK" && POCL_MAX_PTHREAD_COUNT=1 "${CG[@]}" --callgrind-out-file=bp.cg --dump-before="$RENDER" \
  --dump-after="$RENDER" "$CLPATH" bench path "$SCENE" --width "$SIZE" --height "$SIZE" --spp "$SPP" \
  --max-depth "$DEPTH" --rounds 1 --threads 1) > "$WORK/bp.log" 2>&1

python3 - "$WORK" "$OUT/instructions.md" "$(git -C "$ROOT" rev-parse --short HEAD)" "$(date -u '+%Y-%m-%d %H:%M UTC')" \
  "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')" "${SCENE#"$ROOT"/}" "$SIZE" "$SPP" \
  "$DEPTH" "$(valgrind --version)" "$(dpkg-query -W -f='${Version}' embree-tools 2>/dev/null || echo '?')" <<'PY'
import collections, glob, sys
work, out, commit, date, cpu, scene, size, spp, depth, vg, embree = sys.argv[1:]
RTC = ("rtcIntersect1", "rtcOccluded1")

def parse(path):
    """Self instructions per function, and calls to / instructions under the rtc entry points."""
    own, calls, under = collections.Counter(), collections.Counter(), collections.Counter()
    fn = cfn = None
    after_calls = False
    for line in open(path):
        if line.startswith("fn="):
            fn = line[3:].strip()
        elif line.startswith("cfn="):
            cfn = line[4:].strip()
        elif line.startswith("calls="):
            calls[cfn] += int(line[6:].split()[0])
            after_calls = True
        elif line[:1].isdigit() or line[:1] in "+-*":
            f = line.split()
            ir = int(f[1]) if len(f) > 1 else 0
            if after_calls:
                under[cfn] += ir
                after_calls = False
            else:
                own[fn] += ir
    return own, calls, under

def count(path):
    own, calls, under = parse(path)
    total = sum(own.values())
    rays = {k: calls[k] for k in RTC}
    trav = sum(under[k] for k in RTC)
    return dict(total=total, rays=rays, trav=trav, own=own)

one, two = count(f"{work}/pt-0-1.cg"), count(f"{work}/pt-1-1.cg")
pt = dict(total=two["total"] - one["total"], trav=two["trav"] - one["trav"],
          rays={k: two["rays"][k] - one["rays"][k] for k in RTC})
parts = sorted(glob.glob(f"{work}/bp.cg.*"), key=lambda p: int(p.rsplit(".", 1)[1]))
ends = [i for i, p in enumerate(parts) if "Trigger: --dump-after" in open(p).read(4000)]
if len(ends) != 4:
    sys.exit(f"instructions.sh: error: expected 4 renders of the built-in tracer in bench path, found {len(ends)}")
default, robust = count(parts[ends[2]]), count(parts[ends[3]])  # after the two warm-up renders
# The clpath render is the part before the timed default render: its kernels' own instructions.
clp_own, cl_calls, _ = parse(parts[ends[2] - 1])
walk = {f: n for f, n in clp_own.items() if f in ("traverse_tree", "occlude_tree")}
kernel = clp_own.get("_pocl_kernel_render_paths_workgroup", 0)
samples = int(size) ** 2 * int(spp)

rows = []
def row(name, c, rays_closest, rays_any, app):
    rays = rays_closest + rays_any
    rows.append((name, rays / samples, c / rays, app / rays, (c - app) / rays, c / samples))
for name, c in (("Embree's `pathtracer` example", pt), ("built-in Embree path tracer, default mode", default),
                ("built-in Embree path tracer, robust mode", robust)):
    row(name, c["total"], c["rays"]["rtcIntersect1"], c["rays"]["rtcOccluded1"], c["total"] - c["trav"])
L = ["# Instructions per ray: Embree's `pathtracer` example and clpath's built-in Embree path tracer", "",
     f"- Counted by callgrind ({vg}), one thread, on {cpu}; {date}, commit {commit}; Embree {embree} (Debian).",
     f"- Scene `{scene}` at {size}x{size}, {spp} samples per pixel, depth {depth}, the scene and commands of "
     "`pathtracer.sh` (`clpath export --format embree` for the example).",
     "- The example: one frame, the difference of `pathtracer -c scene.ecs --benchmark 1 1 --legacy` (two frames) "
     "and `--benchmark 0 1` (one). The built-in tracer: its timed render in each mode in `clpath bench path "
     "--rounds 1 --threads 1`, cut out by callgrind dumps at the entry and exit of its render.",
     "- Traversal: every instruction under `rtcIntersect1` and `rtcOccluded1` (the same Embree code in both "
     "programs); own code: the rest of the render (camera, shading, light sampling, film).",
     "- Instruction counts are not time (this CPU runs some code at more instructions per cycle than other), "
     "but they are exact and repeatable where this machine's wall time moves by a quarter between processes; "
     "`README.md` beside this file has the wall-time rounds.", "",
     "| tracer | rays per sample | instructions per ray | own code per ray | traversal per ray | per sample |",
     "|---|---:|---:|---:|---:|---:|"]
for name, rps, ipr, app, trav, ips in rows:
    L.append(f"| {name} | {rps:.3f} | {ipr:.0f} | {app:.0f} | {trav:.0f} | {ips:.0f} |")
ref = rows[0]
L += ["", f"The built-in tracer in default mode over the example: **{rows[1][2] / ref[2]:.3f}** the instructions "
      f"per ray, {rows[1][3] / ref[3]:.3f} of the example's own code per ray, {rows[1][4] / ref[4]:.3f} of its "
      "traversal per ray.", ""]
cl_rays = cl_calls["traverse_tree"] + cl_calls["occlude_tree"]
if cl_rays:
    cl_walk = sum(walk.values())
    L += ["clpath's own render in the same run (`clpath bench path`'s timed render, PoCL's kernel compiled for "
          "haswell under valgrind; the kernels' instructions only, not the OpenCL runtime's): "
          f"{cl_rays / samples:.3f} rays per sample, **{(cl_walk + kernel) / cl_rays:.0f}** instructions per ray, "
          f"{kernel / cl_rays:.0f} in the megakernel's own code, {cl_walk / cl_rays:.0f} in its traversal "
          f"(closest hit {walk.get('traverse_tree', 0) / max(cl_calls['traverse_tree'], 1):.0f} per ray over "
          f"{cl_calls['traverse_tree']} rays, any hit {walk.get('occlude_tree', 0) / max(cl_calls['occlude_tree'], 1):.0f} "
          f"over {cl_calls['occlude_tree']}). Embree's traversal over both kinds: "
          f"{default['trav'] / max(sum(default['rays'].values()), 1):.0f} per ray in its default mode, "
          f"{robust['trav'] / max(sum(robust['rays'].values()), 1):.0f} in robust mode, whose watertight triangle "
          "test is the like-for-like one (clpath's is watertight too).", ""]
open(out, "w").write("\n".join(L) + "\n")
print("\n".join(L))
PY
echo "instructions.sh: wrote $OUT/instructions.md"
