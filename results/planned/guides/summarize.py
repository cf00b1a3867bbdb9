"""The table of results/planned/guides/README.md from the JSON files beside this script."""
import json
import pathlib
import statistics

here = pathlib.Path(__file__).parent
rows, seconds = [], []
for k in range(3):
    nav = {c: {r["target"]: r["outcome"] for r in json.loads((here / f"vbeat{k}_nav_{c}.json").read_text())["results"]}
           for c in ("policy", "scripted-omega")}
    for path in sorted(here.glob(f"vbeat{k}_hr60_t*.json"), key=lambda p: int(p.stem.split("_t")[-1])):
        plan = json.loads(path.read_text())
        strict, proc = plan["search"]["strict"], plan["search"].get("procedure", {})
        t = plan["target"]
        seconds.append(strict["seconds"] + proc.get("seconds", 0.0))
        rows.append(f"| tree {k} T{t} | {plan['found']} | {plan.get('guide', 'the search')} | {strict['guided']} of "
                    f"{strict['found']} | {proc.get('found', '-')} | {plan['peak_tip_force_N']:.2f} N | {seconds[-1]:.0f} s | "
                    f"{nav['policy'][t]} | {nav['scripted-omega'][t]} |")
print("| target | plan | chosen | strict plans: guides' of all | procedure plans | peak tip force | planning time | "
      "shipped actor | scripted rule |")
print("|---|---|---|---|---|---|---|---|---|")
print("\n".join(rows))
print(f"\nmedian planning time {statistics.median(seconds):.1f} s over {len(seconds)} targets")
