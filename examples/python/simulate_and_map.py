"""The paper's benchmark for one run, step by step, from Python: obstacle course 4, table test
T, seed 1 -> simulated LMS 200 run -> raw elevation/certainty map (Eq. 1-6) -> CAS and the four
baselines -> PI (Eq. 11). Prints the same PI line as
`casmap bench --courses 4 --tests T --seed 1`.

    python3 simulate_and_map.py [DATA_DIR] [COURSE] [TEST]

DATA_DIR holds scenes/ (an install's share/casmap, or the source tree; default: the source tree).
"""
import math
import pathlib
import sys

import casmap

data = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2]
course = int(sys.argv[2]) if len(sys.argv) > 2 else 4
test = sys.argv[3] if len(sys.argv) > 3 else "T"

# 1. The course and one table run over it (default rig and LMS 200, 1 m/s in test T). The run
#    carries the exact ground truth on the paper's 200 x 80 grid of 25 mm cells.
scene = casmap.load_scene(data / "scenes" / "courses" / f"course{course:02d}.yaml")
run = casmap.simulate(scene, test, seed=1)

# 2. The raw maps on the truth's grid.
raw, certainty, grid = casmap.map_run(run, grid=run.maps.grid, a=3)

# 3. The five filters with the paper's parameters (Eq. 8's s = 25 mm, v = 1 m/s, dt = 1/75 s
#    and a = 3 are the defaults), each scored against the truth over the paper's region.
pis = {}
for method in casmap.FILTER_METHODS:
    filtered, _ = casmap.filter(method, raw, certainty)
    pis[method] = casmap.performance_index(filtered, raw, run.maps.truth_m)

# 4. The line `casmap bench` prints: lower is better, '*' marks the best.
best = min(v for v in pis.values() if math.isfinite(v))
cells = "".join(f"{v:8.3f}{'*' if v == best else ' '}" for v in pis.values())
print(f"{course:6d} {test:<4s} {cells}")
