#!/usr/bin/env bash
# The main job over many pushes: af-sim's humanoid dropped onto the default map with seeds FIRST to
# LAST (each a small deterministic push), one line per seed and the totals: steps to rest, failed
# solves, the largest joint error and penetration. Exits 1 if any drop blew up (NaN) or did not rest.
#
# usage: bench/seeds.sh [FIRST LAST] [--solver tree|exact|pgs]
# env:   AF_SIM (default <repo>/build/tools/af-sim)
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
sim=${AF_SIM:-$root/build/tools/af-sim}
first=0 last=40 solver=tree
positional=()
while [[ $# -gt 0 ]]; do
    case $1 in
        --solver) solver=$2; shift 2 ;;
        *) positional+=("$1"); shift ;;
    esac
done
[[ ${#positional[@]} -ge 1 ]] && first=${positional[0]}
[[ ${#positional[@]} -ge 2 ]] && last=${positional[1]}
[[ -x $sim ]] || { echo "seeds.sh: no af-sim at $sim (cmake --build build --target af-sim)" >&2; exit 2; }

printf '%5s %6s %8s %8s %12s %12s\n' seed steps rest_s failed joint_error penetration
for ((s = first; s <= last; ++s)); do
    { "$sim" --solver "$solver" --seed "$s" --json || true; } |
        python3 -c '
import json, sys
j = json.load(sys.stdin)
rest = j["rest_time_s"]
print("%5d %6d %8s %8d %12.3g %12.3g %d" % (int(sys.argv[1]), j["steps"], "-" if rest is None else "%.2f" % rest,
      j["solver_failures"], j["max_joint_error"], j["max_penetration"], 1 if (j["invalid_motion"] or rest is None) else 0))
' "$s"
done | awk '
    { printf "%5s %6s %8s %8s %12s %12s\n", $1, $2, $3, $4, $5, $6; steps += $2; failed += $4; bad += $7
      if ($5 > joint) joint = $5; if ($6 > pen) pen = $6; n++ }
    END { printf "seeds %d: %d steps, %d failed solves, joints within %.3g units, penetration %.3g units\n",
                 n, steps, failed, joint, pen
          exit bad > 0 }'
