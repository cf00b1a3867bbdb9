"""Per episode of a `navigate --out DIR` run: outcome, omega while the actor is in control (median, share of
steps at or below -0.95), how much it rolls (share of steps with |rotation action| > 0.5) and where the tip ends.

in:  one or more navigate output folders (their episode*_target*.json trajectories)
out: one line per episode on stdout
Used for results/junctions/README.md, "Correction": python3 results/junctions/omega_traces.py runs/t5_separate ...
"""
import glob
import json
import os
import statistics
import sys

for folder in sys.argv[1:]:
    for path in sorted(glob.glob(os.path.join(folder, "episode*_target*.json"))):
        t = json.load(open(path))
        f, names = t["frames"], t["observation_names"]
        io = names.index("omega")
        steps = [i for i, c in enumerate(f["agent_in_control"]) if c and i > 0]
        omega = [f["observation"][i][io] for i in steps]
        rolling = sum(abs(f["action"][i]) > 0.5 for i in steps) / max(1, len(steps))
        aimed = sum(w <= -0.95 for w in omega) / max(1, len(omega))
        tip = ", ".join(f"{x:.1f}" for x in f["tip"][-1])
        print(f"{os.path.basename(folder)} {os.path.basename(path)[:-5]} seed {t['seed']}: {t['outcome']}, "
              f"{len(f['tip']) - 1} steps; omega median {statistics.median(omega):+.2f}, at <= -0.95 {aimed:.0%}; "
              f"rolling {rolling:.0%}; tip ends at ({tip})")
