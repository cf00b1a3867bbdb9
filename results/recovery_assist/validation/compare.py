"""The validation-tree check of results/recovery_assist/README.md (standard library only): the navigate --json files
beside this one. Where both runs exist (<tree>_alone.json, <tree>_assist.json) the actor alone against assisted,
episode by episode, and the assist against the assist before its standstill trigger (before_standstill/); for every
assisted run its procedures that did not reach the target, with how they ended."""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
TREES = ["rca_validation", "rca_validation_deformed", "pl_validation", "syn_validation"]
STAGES = ["recovery", "reshape"]


def load(tree, kind, folder=""):
    path = os.path.join(HERE, folder, f"{tree}_{kind}.json")
    if not os.path.exists(path):
        return None
    return {(r["target"], r["seed"]): r for r in json.load(open(path))["results"]}


def reached(results, stage):
    return {k for k, r in results.items() if r[stage]["outcome"] == "success"}


def main():
    for tree in TREES:
        alone, assisted, before = load(tree, "alone"), load(tree, "assist"), load(tree, "assist", "before_standstill")
        if assisted is None:
            continue
        n = len(assisted)
        strict = sum(r["outcome"] == "success" for r in assisted.values())
        print(f"{tree}: strict {strict}/{n}")
        for stage in STAGES:
            line = f"  with {stage}: assisted {len(reached(assisted, stage))}/{n}"
            if alone is not None:
                a, b = reached(alone, stage), reached(assisted, stage)
                line += f", alone {len(a)}/{len(alone)}, won {len(b - a)} lost {len(a - b)}"
            if before is not None:
                a, b = reached(before, stage), reached(assisted, stage)
                line += f"; before the standstill trigger {len(a)}/{len(before)}, won {len(b - a)} lost {len(a - b)}"
            print(line)
        for (target, seed), r in sorted(assisted.items()):
            if r["reshape"]["outcome"] != "success":
                print(f"  not reached: T{target} seed {seed}: first pass {r['recovery']['outcome']} after "
                      f"{r['recovery']['attempts']} pull-backs ({r['recovery']['detail'] or r['detail']}); "
                      f"reshaped pass {r['reshape']['outcome']} ({r['reshape']['detail']})")


if __name__ == "__main__":
    main()
