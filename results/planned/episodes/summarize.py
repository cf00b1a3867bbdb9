"""The per-episode planned figures of results/planned/episodes as one markdown table (docs/results.md,
docs/planning.md): per row, the episodes planned from their own starts and each column against them.
    python3 results/planned/episodes/summarize.py [results.json ...]"""
import json
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
COLUMNS = (("sac-policy", "shipped actor"), ("scripted-omega", "scripted rule"))


def rows_of(paths):
    for path in paths:
        for row in json.loads(pathlib.Path(path).read_text())["rows"]:
            if "planned" in row and "per_episode" in row["planned"]:
                yield row


def line(row):
    p = row["planned"]
    cells = [row["name"], str(p["episodes"]), f"{p['planned']} ({p['strict']})"]
    for column, _ in COLUMNS:
        c = p["columns"].get(column)
        cells.append("-" if c is None else f"{c['reached']}, {c['planned_not_reached']}")
    found = [e for e in p["per_episode"] if e["found"] != "none"]
    cells.append(f"{max(e['peak_tip_force_N'] for e in found):.2f} N" if found else "-")
    cells.append(f"{p['median_seconds']:.1f} s")
    return "| " + " | ".join(cells) + " |"


def main(paths):
    head = ["row", "episodes", "planned (strict)"] + [f"{name}: reached, missed but planned" for _, name in COLUMNS]
    head += ["highest peak tip force of a plan", "median planning time"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    total = {"episodes": 0, "planned": 0}
    for row in rows_of(paths):
        print(line(row))
        total["episodes"] += row["planned"]["episodes"]
        total["planned"] += row["planned"]["planned"]
        for column, _ in COLUMNS:
            c = row["planned"]["columns"].get(column, {})
            for k in ("reached", "planned_not_reached", "reached_not_planned"):
                total[f"{column} {k}"] = total.get(f"{column} {k}", 0) + c.get(k, 0)
    print()
    print("Over all rows: " + ", ".join(f"{k} {v}" for k, v in total.items()))


if __name__ == "__main__":
    main(sys.argv[1:] or [HERE / "results.json"])
