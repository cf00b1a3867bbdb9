"""results/bench/equivalence.py: an engine change's outcomes on the table, episode by episode, before and after."""
import json
import subprocess
import sys

from guidewire_nav import REPO_ROOT

SCRIPT = REPO_ROOT / "results" / "bench" / "equivalence.py"


def episode(seed, outcome, steps):
    return {"anatomy": "a", "target": 1, "seed": seed, "outcome": outcome, "steps": steps}


def write(path, rows):
    path.write_text(json.dumps({"rows": [{"name": name, "results": {c: {"results": e} for c, e in columns.items()}}
                                         for name, columns in rows.items()]}))
    return str(path)


def test_counts_kept_outcomes_and_steps_and_lists_the_changed_episodes(tmp_path):
    before = write(tmp_path / "before.json", {
        "row": {"rule": [episode(0, "success", 10), episode(1, "success", 12), episode(2, "wrong_branch", 5)],
                "push-only": [episode(0, "stuck", 30)]},
        "other": {"rule": [episode(0, "success", 7)]}})
    after = write(tmp_path / "after.json", {
        "row": {"rule": [episode(0, "success", 10), episode(1, "wrong_branch", 9), episode(2, "wrong_branch", 6),
                         episode(3, "success", 4)],
                "push-only": [episode(0, "stuck", 30)]}})
    out = json.loads(subprocess.run([sys.executable, str(SCRIPT), before, after], capture_output=True, text=True,
                                    check=True).stdout)
    rule = out["rows"]["row"]["rule"]
    assert (rule["episodes"], rule["same_outcome"], rule["same_outcome_and_steps"]) == (3, 2, 1)  # seed 3: after only
    assert (rule["success_before"], rule["success_after"], rule["only_before"], rule["only_after"]) == (2, 1, 1, 0)
    assert list(out["rows"]) == ["row"]  # "other" did not run after: left out
    total = out["all"]
    assert (total["episodes"], total["same_outcome"], total["share_same_outcome"]) == (4, 3, 0.75)
    assert out["changed"] == [{"row": "row", "controller": "rule", "anatomy": "a", "target": 1, "seed": 1,
                               "before": "success", "after": "wrong_branch"}]
    missing = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path / "none.json"), after], capture_output=True,
                             text=True)
    assert missing.returncode != 0 and "none.json: no such file" in missing.stderr
