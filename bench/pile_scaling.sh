#!/usr/bin/env bash
# How the cost of a pile grows with its figures (issue #28): the pile scene of docs/bench-scene.md
# with N ragdolls dropped onto each other, our tree solver and Bullet's sequential impulses (when
# Debian's Bullet is installed) in one run, as a table of µs per step while the figures move
# (until the rest step, the whole run when they never rest) and, with --svg, a plot of it against
# N. A cost that grows linearly with the figures is a straight line on it.
#
# usage: bench/pile_scaling.sh [--counts "1 2 4 8 16 32"] [--steps N] [--max-seconds S]
#                              [--svg FILE] [--no-install]
# env:   BUILD_DIR (default <repo>/build-bench), JOBS (default 2)
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build-bench}
jobs=${JOBS:-2}
counts="1 2 4 8 16 32" steps=600 max_seconds=300 svg="" install=1
while [[ $# -gt 0 ]]; do
    case $1 in
        --counts) counts=$2; shift 2 ;;
        --steps) steps=$2; shift 2 ;;
        --max-seconds) max_seconds=$2; shift 2 ;;
        --svg) svg=$2; shift 2 ;;
        --no-install) install=0; shift ;;
        *) echo "usage: $0 [--counts \"N ...\"] [--steps N] [--max-seconds S] [--svg FILE] [--no-install]" >&2
           exit 2 ;;
    esac
done

if [[ $install == 1 ]] && ! pkg-config --exists bullet 2>/dev/null; then
    sudo=""
    [[ $(id -u) == 0 ]] || sudo=sudo
    $sudo apt-get install -y libbullet-dev
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAF_BUILD_BENCH=ON >/dev/null
available=$(cmake --build "$build" --target help | sed -n 's/^\.\.\. \([^ ]*\).*/\1/p; s/^\([^: ]*\): .*/\1/p')
targets=(af-bench-scene)
grep -qx bullet-bench-scene <<<"$available" && targets+=(bullet-bench-scene)
cmake --build "$build" -j"$jobs" --target "${targets[@]}" >/dev/null
program() { find "$build" -type f -name "$1" -perm -u+x | head -n 1; }

results=$(mktemp)
trap 'rm -f "$results"' EXIT
for n in $counts; do
    common=(--scene pile --count "$n" --steps "$steps" --max-seconds "$max_seconds" --sleep off)
    "$(program af-bench-scene)" "${common[@]}" --solver tree >>"$results" || echo "pile_scaling.sh: af, $n figures, failed" >&2
    if [[ ${#targets[@]} -gt 1 ]]; then
        "$(program bullet-bench-scene)" "${common[@]}" --variant si10 >>"$results" ||
            echo "pile_scaling.sh: Bullet, $n figures, failed" >&2
    fi
done

python3 - "$results" "$svg" <<'PY'
import json, math, os, sys
rows = [json.loads(l) for l in open(sys.argv[1]) if l.strip().startswith("{")]
svg_path = sys.argv[2]
def series(engine):
    return {r["ragdolls"]: r for r in rows if r["engine"].startswith(engine) and not r["engine"].endswith("f64")}
af, bullet = series("af"), series("bullet")
print("pile: µs per step while the figures move (until the rest step; * stopped by --max-seconds)")
print(f"{'figures':>7} {'bodies':>6} {'af_us':>10} {'af_us/fig':>9} {'bullet_us':>10} {'ratio':>6} {'af_joint_m':>10} {'af_rest':>7}")
for n in sorted(af):
    a, b = af[n], bullet.get(n)
    us = a["us_per_step_mean_until_rest"]
    cells = [f"{n:>7}", f"{16 * n:>6}", f"{us:>10.1f}{'*' if a.get('partial') else ''}", f"{us / n:>9.1f}"]
    if b:
        cells += [f"{b['us_per_step_mean_until_rest']:>10.1f}", f"{us / b['us_per_step_mean_until_rest']:>5.1f}x"]
    else:
        cells += [f"{'-':>10}", f"{'-':>6}"]
    cells += [f"{a['joint_err_max_m']:>10.2g}", f"{str(a.get('rest_step') or '-'):>7}"]
    print(" ".join(cells))
if not svg_path or not af:
    sys.exit(0)

# A log-log plot: a cost linear in the figures is a line of slope 1 (the dotted guide).
W, H, L, R, T, B = 640, 420, 70, 150, 30, 50
points = {"af tree": [(n, af[n]["us_per_step_mean_until_rest"]) for n in sorted(af)],
          "Bullet si10": [(n, bullet[n]["us_per_step_mean_until_rest"]) for n in sorted(bullet)]}
values = [v for s in points.values() for _, v in s]
xs = [n for s in points.values() for n, _ in s]
x0, x1 = math.log10(min(xs)), math.log10(max(xs)) if max(xs) > min(xs) else math.log10(min(xs)) + 1
y0, y1 = math.floor(math.log10(min(values))), math.ceil(math.log10(max(values)))
def px(n): return L + (math.log10(n) - x0) / (x1 - x0) * (W - L - R)
def py(v): return H - B - (math.log10(v) - y0) / (y1 - y0) * (H - T - B)
out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
       f'<rect width="{W}" height="{H}" fill="white"/>']
for e in range(y0, y1 + 1):
    y = py(10 ** e)
    out.append(f'<line x1="{L}" y1="{y:.1f}" x2="{W - R}" y2="{y:.1f}" stroke="#ddd"/>')
    out.append(f'<text x="{L - 6}" y="{y + 4:.1f}" text-anchor="end">{10 ** e:,}</text>')
for n in sorted(set(xs)):
    x = px(n)
    out.append(f'<line x1="{x:.1f}" y1="{T}" x2="{x:.1f}" y2="{H - B}" stroke="#eee"/>')
    out.append(f'<text x="{x:.1f}" y="{H - B + 16}" text-anchor="middle">{n}</text>')
out.append(f'<text x="{(L + W - R) / 2}" y="{H - 10}" text-anchor="middle">figures in the pile (16 bodies each)</text>')
out.append(f'<text x="16" y="{(T + H - B) / 2}" text-anchor="middle" transform="rotate(-90 16 {(T + H - B) / 2})">'
           'µs per step while the figures move</text>')
colours = {"af tree": "#c0392b", "Bullet si10": "#2c3e50"}
for k, (name, s) in enumerate(points.items()):
    if not s:
        continue
    path = " ".join(f"{px(n):.1f},{py(v):.1f}" for n, v in s)
    out.append(f'<polyline points="{path}" fill="none" stroke="{colours[name]}" stroke-width="2"/>')
    out += [f'<circle cx="{px(n):.1f}" cy="{py(v):.1f}" r="3" fill="{colours[name]}"/>' for n, v in s]
    n0, v0 = s[0]
    guide = [(n, v0 * n / n0) for n, _ in s]
    out.append('<polyline points="' + " ".join(f"{px(n):.1f},{py(v):.1f}" for n, v in guide) +
               f'" fill="none" stroke="{colours[name]}" stroke-dasharray="3,4" stroke-width="1"/>')
    ly = T + 20 + 20 * k
    out.append(f'<line x1="{W - R + 12}" y1="{ly}" x2="{W - R + 34}" y2="{ly}" stroke="{colours[name]}" stroke-width="2"/>')
    out.append(f'<text x="{W - R + 40}" y="{ly + 4}">{name}</text>')
out.append(f'<text x="{W - R + 12}" y="{T + 70}" fill="#555">dotted: linear</text>')
out.append('</svg>')
with open(svg_path + ".tmp", "w") as f:
    f.write("\n".join(out) + "\n")
os.replace(svg_path + ".tmp", svg_path)
print(f"plot: {svg_path}")
PY
