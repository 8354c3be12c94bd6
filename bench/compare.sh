#!/usr/bin/env bash
# Issue #4's side-by-side comparison: ODE and Bullet (Debian's packages) and our af-bench-scene on
# one ragdoll scene of docs/bench-scene.md, every engine/variant once, as a table plus the ratios of our
# solvers' mean µs/step to Bullet si10's.
#
# With --instructions, every engine/variant runs once more under callgrind, counting the
# instructions of its step calls alone (bench/scene/counted_step.h): a measure the machine's load
# does not move, reported per step and as ratios to Bullet si10's too.
#
# The honest cost is that of the steps in which figures move: us_moving is the mean until the
# rest step (the whole run when the figures never rest), beside the whole run's mean, which the
# cheap resting steps dilute. --scene all runs the four scenes one after another and ends with
# one summary table of af tree against Bullet si10.
#
# usage: bench/compare.sh [--scene single|grid4|grid16|pile|all] [--count N] [--steps N]
#                         [--max-seconds S] [--sleep on|off] [--instructions] [--no-install]
# env:   BUILD_DIR (default <repo>/build-bench), JOBS (default 2)
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build-bench}
jobs=${JOBS:-2}
scene=single count=0 steps=600 max_seconds=120 sleep=off install=1 instructions=0
while [[ $# -gt 0 ]]; do
    case $1 in
        --scene) scene=$2; shift 2 ;;
        --count) count=$2; shift 2 ;;
        --steps) steps=$2; shift 2 ;;
        --max-seconds) max_seconds=$2; shift 2 ;;
        --sleep) sleep=$2; shift 2 ;;
        --instructions) instructions=1; shift ;;
        --no-install) install=0; shift ;;
        *) echo "usage: $0 [--scene S|all] [--count N] [--steps N] [--max-seconds S] [--sleep on|off] [--instructions] [--no-install]" >&2
           exit 2 ;;
    esac
done

if [[ $install == 1 ]] && ! pkg-config --exists ode bullet 2>/dev/null; then
    sudo=""
    [[ $(id -u) == 0 ]] || sudo=sudo
    $sudo apt-get install -y libode-dev libbullet-dev
fi
if [[ $instructions == 1 ]] && ! command -v valgrind >/dev/null; then
    echo "compare.sh: --instructions needs valgrind (apt-get install valgrind)" >&2
    exit 1
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAF_BUILD_BENCH=ON >/dev/null
# Build what this tree has: the peers exist only where the packages are, af-bench-scene only once written.
# (Makefiles list "... target", Ninja "target: phony".)
available=$(cmake --build "$build" --target help | sed -n 's/^\.\.\. \([^ ]*\).*/\1/p; s/^\([^: ]*\): .*/\1/p')
targets=()
for t in af-bench-scene ode-bench-scene bullet-bench-scene bullet-f64-bench-scene; do
    if grep -qx "$t" <<<"$available"; then targets+=("$t"); else echo "compare.sh: no target $t, skipped" >&2; fi
done
[[ ${#targets[@]} -gt 0 ]] || { echo "compare.sh: nothing to run" >&2; exit 1; }
cmake --build "$build" -j"$jobs" --target "${targets[@]}" >/dev/null

program() { find "$build" -type f -name "$1" -perm -u+x | head -n 1; }
results=$(mktemp)
counts=$(mktemp)
callgrind_dir=$(mktemp -d)
trap 'rm -rf "$results" "$counts" "$callgrind_dir"' EXIT
scenes=("$scene")
[[ $scene == all ]] && scenes=(single grid4 grid16 pile)
summary=$(mktemp)
trap 'rm -rf "$results" "$counts" "$callgrind_dir" "$summary"' EXIT
for scene in "${scenes[@]}"; do
: >"$results"
: >"$counts"
common=(--scene "$scene" --steps "$steps" --max-seconds "$max_seconds" --sleep "$sleep")
[[ $count -gt 0 && $scene == pile ]] && common+=(--count "$count")
for t in "${targets[@]}"; do
    exe=$(program "$t")
    case $t in
        af-bench-scene) runs=("--solver tree" "--solver tree --threads 2" "--solver exact" "--solver pgs") ;;
        ode-bench-scene) runs=("--variant dantzig" "--variant quickstep20") ;;
        *) runs=("--variant si10" "--variant mlcp_dantzig") ;;
    esac
    for r in "${runs[@]}"; do
        # shellcheck disable=SC2086 # r is two words on purpose
        if ! "$exe" "${common[@]}" $r >>"$results"; then
            echo "compare.sh: $t $r failed" >&2
        fi
        [[ $instructions == 1 ]] || continue
        # One line per run: the instructions of its step calls, then its own JSON.
        out="$callgrind_dir/callgrind.out"
        if json=$(valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$out" \
                      "$exe" "${common[@]}" $r 2>/dev/null); then
            echo "$(sed -n 's/^totals: *\([0-9]*\).*/\1/p' "$out") $json" >>"$counts"
        else
            echo "compare.sh: $t $r failed under callgrind" >&2
        fi
    done
done

cat "$results" >>"$summary"
python3 - "$results" "$counts" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip().startswith("{")]
counted = []
for line in open(sys.argv[2]):
    number, _, text = line.partition(" ")
    if number.isdigit() and text.strip().startswith("{"):
        counted.append((int(number), json.loads(text)))
def num(v, f):
    return "-" if v is None else f.format(v)
cols = [("engine", 18, "{}"), ("variant", 13, "{}"), ("us_moving", 9, "{:.1f}"), ("us_mean", 9, "{:.1f}"),
        ("us_median", 9, "{:.1f}"),
        ("joint_err_max_m", 15, "{:.3g}"), ("ang_err_max", 11, "{:.3g}"), ("limit_viol_max", 14, "{:.3g}"),
        ("ground_pen_max_m", 16, "{:.3g}"), ("energy_gain_J", 13, "{:.3g}"), ("rest_step", 9, "{}"),
        ("exploded", 8, "{}")]
keys = {"us_moving": "us_per_step_mean_until_rest", "us_mean": "us_per_step_mean", "us_median": "us_per_step_median", "limit_viol_max": "limit_viol_max_rad",
        "ang_err_max": "joint_ang_err_max_rad",
        "energy_gain_J": "energy_gain_max_J"}
print(f"scene {rows[0]['scene'] if rows else '?'} ({rows[0]['ragdolls'] if rows else '?'} ragdolls): "
      "µs per step (step call only; us_moving until the rest step), errors over the run")
print(" ".join(f"{c:>{w}}" for c, w, _ in cols))
for r in rows:
    cells = []
    for c, w, f in cols:
        v = r.get(keys.get(c, c))
        if isinstance(v, bool): v = str(v).lower()
        if c == "variant" and r.get("partial"): v = f"{v}*"
        cells.append(f"{num(v, f):>{w}}")
    print(" ".join(cells))
if any(r.get("partial") for r in rows):
    print("* partial: stopped by --max-seconds")
si10 = [r for r in rows if r["engine"].startswith("bullet") and not r["engine"].endswith("f64") and r["variant"] == "si10"]
ours = [r for r in rows if r["engine"].startswith("af")]
if si10 and ours:
    base = si10[0]["us_per_step_mean"]
    median = si10[0]["us_per_step_median"]
    moving = si10[0]["us_per_step_mean_until_rest"]
    print(f"\nµs/step relative to {si10[0]['engine']} si10 (moving {moving:.1f} µs, mean {base:.1f} µs, "
          f"median {median:.1f} µs):")
    for r in ours:
        print(f"  {r['engine']} {r['variant']}: moving {r['us_per_step_mean_until_rest'] / moving:.2f}x, "
              f"mean {r['us_per_step_mean'] / base:.2f}x, median {r['us_per_step_median'] / median:.2f}x")
print("\nmean µs/step until the figures rest, and from then on (rest_step as above):")
for r in rows:
    until, after = r.get("us_per_step_mean_until_rest"), r.get("us_per_step_mean_at_rest")
    print(f"  {r['engine']} {r['variant']}: {num(until, '{:.1f}')} until step {num(r.get('rest_step'), '{}')}, "
          f"{num(after, '{:.1f}')} after")
if counted:
    print("\ninstructions per step (callgrind, step calls only; the same for every run of a build):")
    per_step = [(r, n / max(1, r["steps_done"])) for n, r in counted]
    for r, k in per_step:
        print(f"  {r['engine']} {r['variant']}: {k / 1e3:.1f}k")
    base = [k for r, k in per_step if r["engine"] == "bullet-3.24" and r["variant"] == "si10"]
    if base:
        print(f"relative to bullet-3.24 si10 ({base[0] / 1e3:.1f}k):")
        for r, k in per_step:
            if r["engine"].startswith("af"):
                print(f"  {r['engine']} {r['variant']}: {k / base[0]:.2f}x")
PY
done

[[ ${#scenes[@]} -gt 1 ]] || exit 0
python3 - "$summary" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip().startswith("{")]
def pick(scene, engine, variant):
    for r in rows:
        if r["scene"] == scene and r["engine"].startswith(engine) and not r["engine"].endswith("f64") and r["variant"] == variant:
            return r
print("\nsummary: af tree against Bullet si10, µs per step while figures move (until the rest step)")
print(f"{'scene':>7} {'bodies':>6} {'af_us':>9} {'bullet_us':>9} {'ratio':>6} {'af_joint_m':>10} {'bullet_joint_m':>14} "
      f"{'af_pen_m':>8} {'af_gain_J':>9} {'af_rest':>7} {'failures':>8}")
for scene in ("single", "grid4", "grid16", "pile"):
    a, b = pick(scene, "af", "tree"), pick(scene, "bullet", "si10")
    if not a or not b:
        continue
    ratio = a["us_per_step_mean_until_rest"] / b["us_per_step_mean_until_rest"]
    rest = a.get("rest_step")
    print(f"{scene:>7} {a['ragdolls'] * 16:>6} {a['us_per_step_mean_until_rest']:>9.1f} {b['us_per_step_mean_until_rest']:>9.1f} "
          f"{ratio:>5.2f}x {a['joint_err_max_m']:>10.2g} {b['joint_err_max_m']:>14.2g} {a['ground_pen_max_m']:>8.2g} "
          f"{a['energy_gain_max_J']:>9.2g} {('-' if rest is None else rest):>7} {a.get('solver_failures', '-'):>8}")
PY
