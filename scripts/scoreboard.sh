#!/usr/bin/env bash
# The scoreboard of issue 10 section 5, reproducibly: every named pipeline (`casmap bench
# --pipelines all`) on the 16 obstacle courses x T, TR, TP, TRP and on terrain runs (the outdoor
# scene, vehicle, and the terrain samples of a generated dataset), then docs/results.md's
# "Scoreboard" section regenerated from the bench.json files by scripts/scoreboard.py.
#
#   scripts/scoreboard.sh [--casmap PATH] [--seed N] [--preset NAME] [--out DIR]
#                         [--threads N] [--samples N] [--no-write]
#
# --casmap   the casmap binary (default: build/apps/casmap/casmap)
# --seed     simulator seed(s) of the course runs, e.g. 3 or 3,7 (default 1); the terrain
#            runs use the first
# --preset   filter-parameter preset (default paper: the paper's values), or a comma list of
#            presets merged into one: their `pipelines:` sections, a later preset's section
#            replacing an earlier one's for the same pipeline; their `set:` must agree
# --out      working directory for the bench outputs (default out/scoreboard)
# --samples  dataset samples generated (config/datasets/default.yaml); the terrain ones are
#            benched (default 16)
# --no-write print the section instead of replacing it in docs/results.md
# Runs under `nice -n 10`. Exit status: casmap's (2 for bad input) or 1.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
casmap="$root/build/apps/casmap/casmap"
seed=1
preset=paper
out="out/scoreboard"
threads=2
samples=16
write=1
while [[ $# -gt 0 ]]; do
    case "$1" in
        --casmap) casmap="$2"; shift 2 ;;
        --seed) seed="$2"; shift 2 ;;
        --preset) preset="$2"; shift 2 ;;
        --out) out="$2"; shift 2 ;;
        --threads) threads="$2"; shift 2 ;;
        --samples) samples="$2"; shift 2 ;;
        --no-write) write=0; shift ;;
        -h|--help) sed -n 2,20p "$0"; exit 0 ;;
        *) echo "scoreboard.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
done
if [[ ! -x "$casmap" ]]; then
    echo "scoreboard.sh: --casmap $casmap is not an executable (build casmap first)" >&2
    exit 2
fi
py=/usr/bin/python3
mkdir -p "$out"
run() { echo "+ $*" >&2; nice -n 10 "$@"; }
IFS=',' read -r -a seeds <<< "$seed"
bench_preset="$preset"
if [[ "$preset" == *,* ]]; then
    bench_preset="$out/merged_preset.yaml"
    "$py" - "$root/config/presets" "$preset" "$bench_preset" <<'EOF'
import os, sys, yaml
folder, names, out = sys.argv[1], sys.argv[2].split(","), sys.argv[3]
shared, sections = None, {}
for name in names:
    path = name if ("/" in name or name.endswith(".yaml")) else os.path.join(folder, name + ".yaml")
    try:
        data = yaml.load(open(path), Loader=yaml.BaseLoader) or {}  # scalars as text
    except OSError as e:
        print(f"scoreboard.sh: --preset {name}: {e}", file=sys.stderr)
        sys.exit(2)
    s = data.get("set") or {}
    if shared is not None and s != shared:
        print(f"scoreboard.sh: --preset {name}: set: {s} differs from the earlier presets' "
              f"{shared} (merged presets must share set:)", file=sys.stderr)
        sys.exit(2)
    shared = s
    sections.update(data.get("pipelines") or {})
with open(out, "w") as f:
    f.write(f"# merged by scripts/scoreboard.sh from {', '.join(names)} (later sections win)\n")
    yaml.safe_dump({"description": "merged: " + ", ".join(names), "set": shared,
                    "pipelines": sections}, f, sort_keys=False)
EOF
fi
common=(--pipelines all --seed "${seeds[0]}" --preset "$bench_preset" --no-sheets --threads "$threads")

# 1. The paper's courses, every test, per seed.
courses=()
for s in "${seeds[@]}"; do
    run "$casmap" bench --courses 1-16 --tests T,TR,TP,TRP --pipelines all --seed "$s" \
        --preset "$bench_preset" --no-sheets --threads "$threads" --out "$out/courses_s$s" \
        > "$out/courses_s$s.log"
    courses+=(--courses "$out/courses_s$s/bench.json")
done
terrain=("outdoor (vehicle)=$out/outdoor/bench.json")
# 2. The outdoor scene, driven.
run "$casmap" bench --scenes "$root/scenes/outdoor.yaml" --motion vehicle "${common[@]}" \
    --out "$out/outdoor" > "$out/outdoor.log"
# 3. Generated terrain: the samples of the default dataset spec whose scene is terrain, each with
#    its own drawn rig, sensor and motion.
run "$casmap" dataset --spec "$root/config/datasets/default.yaml" --out "$out/dataset" \
    --count "$samples" --threads "$threads" > "$out/dataset.log"
while IFS=' ' read -r index motion; do
    dir="$out/dataset/samples/$index"
    run "$casmap" bench --scenes "$dir/scene.yaml" --rig "$dir/rig.yaml" \
        --sensor "$dir/sensor.yaml" --motion "$motion" "${common[@]}" \
        --out "$out/terrain_$index" > "$out/terrain_$index.log"
    terrain+=("$index ($motion)=$out/terrain_$index/bench.json")
done < <("$py" - "$out/dataset/manifest.jsonl" <<'EOF'
import json, re, sys
for line in open(sys.argv[1]):
    s = json.loads(line)
    if s.get("status") == "ok" and s["scene"]["type"] == "terrain":
        motion = re.search(r"--motion (\S+)", s["simulate"]).group(1)
        print(f"{s['dir'].rstrip('/').split('/')[-1]} {motion}")
EOF
)

command="scripts/scoreboard.sh --seed $seed --preset $preset --samples $samples --threads $threads"
args=("${courses[@]}" --command "$command" --seed "$seed" --preset "$preset"
      --commit "$(git -C "$root" describe --always --dirty 2>/dev/null || echo unknown)")
for t in "${terrain[@]}"; do
    args+=(--terrain "$t")
done
if [[ $write -eq 1 ]]; then
    "$py" "$root/scripts/scoreboard.py" "${args[@]}" --results "$root/docs/results.md"
    echo "scoreboard.sh: docs/results.md \"Scoreboard\" regenerated" >&2
else
    "$py" "$root/scripts/scoreboard.py" "${args[@]}"
fi
