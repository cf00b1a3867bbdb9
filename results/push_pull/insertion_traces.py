"""Per episode of a `navigate --out DIR` run of a push/pull actor (act/2): outcome, and how it used the insertion:
its mean, the share of steps pulling (< 0) and within 0.1 of zero, and how often a push turned into a pull.

in:  one or more navigate output folders (their episode*_target*.json trajectories)
out: one line per episode on stdout
Used for results/push_pull/README.md, "How the lost episodes use the insertion".
"""
import glob
import json
import os
import sys

for folder in sys.argv[1:]:
    for path in sorted(glob.glob(os.path.join(folder, "episode*_target*.json"))):
        t = json.load(open(path))
        ins = t["frames"]["insertion"][1:]  # the reset frame holds no action
        n = max(1, len(ins))
        flips = sum(1 for a, b in zip(ins, ins[1:]) if a >= 0 > b)
        outcome = t["outcome"] + (f", with recovery {t['recovery']['outcome']}" if "recovery" in t else "")
        print(f"{os.path.basename(folder)} {t['anatomy']} target {t['target_id']} seed {t['seed']}: {outcome}, {len(ins)} steps; "
              f"insertion mean {sum(ins) / n:+.2f}, pulling {sum(x < 0 for x in ins) / n:.0%}, "
              f"within 0.1 of 0 {sum(abs(x) < 0.1 for x in ins) / n:.0%}, push -> pull {flips}")
