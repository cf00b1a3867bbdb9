"""results/generalist/compare.py: two actors paired on the same episodes by the procedure figure at a safe tip force."""
import json
import subprocess
import sys

from guidewire_nav import REPO_ROOT

SCRIPT = REPO_ROOT / "results" / "generalist" / "compare.py"


def episode(seed, outcome, tip_n):
    return {"anatomy": "a", "target": 1, "seed": seed, "outcome": "wrong_branch",
            "recovery": {"outcome": outcome, "force": {"peak_tip_N": tip_n}}}


def write(path, episodes, column="sac-policy", rows=("pool",)):
    path.write_text(json.dumps({"rows": [{"name": row, "results": {column: {"results": episodes}}} for row in rows]}))
    return str(path)


def test_pairs_episodes_and_counts_a_success_over_the_safe_tip_force_as_a_loss(tmp_path):
    a = write(tmp_path / "a.json", [episode(0, "success", 0.2), episode(1, "success", 0.2), episode(2, "success", 2.0),
                                    episode(3, "wrong_branch", 0.1), episode(9, "success", 0.1)])
    b = write(tmp_path / "b.json", [episode(0, "success", 0.3), episode(1, "stuck", 0.2), episode(2, "success", 0.4),
                                    episode(3, "success", 0.1)])
    out = json.loads(subprocess.run([sys.executable, str(SCRIPT), a, b], capture_output=True, text=True,
                                    check=True).stdout)
    fig = out["all"]
    assert (fig["episodes"], fig["a"], fig["b"], fig["a_only"], fig["b_only"], fig["unmatched"]) == (4, 2, 3, 1, 2, 1)
    assert fig["p"] == 1.0  # 1 against 2: the exact sign test
    missing = subprocess.run([sys.executable, str(SCRIPT), a, str(tmp_path / "none.json")], capture_output=True,
                             text=True)
    assert missing.returncode != 0 and "none.json" in missing.stderr


def test_an_actor_against_the_rule_in_its_own_folder_with_the_strict_figure_beside_it(tmp_path):
    a = write(tmp_path / "a.json", [episode(0, "success", 0.2), episode(1, "success", 0.2)], rows=("pool", "later"))
    rule = [dict(episode(0, "success", 0.3), outcome="success"), episode(1, "stuck", 0.2)]
    b = write(tmp_path / "b.json", rule, column="scripted-omega")
    run = [sys.executable, str(SCRIPT), a, b, "--column", "sac-policy,scripted-omega"]
    out = json.loads(subprocess.run(run, capture_output=True, text=True, check=True).stdout)
    assert list(out["rows"]) == ["pool"]  # the rule has not run "later" yet: left out, not counted as lost
    fig = out["all"]
    assert (fig["episodes"], fig["a"], fig["b"], fig["a_only"], fig["b_only"]) == (2, 2, 1, 1, 0)
    assert (fig["a_strict"], fig["b_strict"]) == (0, 1)  # A reached both only after pulling out of a wrong branch
    table = subprocess.run(run + ["--markdown"], capture_output=True, text=True, check=True).stdout.splitlines()
    assert table[0].startswith("| row | episodes | sac-policy: procedure") and "scripted-omega: strict" in table[0]
    assert table[2] == "| pool | 2 | 2 | 1 | 1 | 0 | 1 | 0 | 1 |" and table[3].startswith("| all rows | 2 |")
