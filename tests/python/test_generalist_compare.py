"""results/generalist/compare.py: two actors paired on the same episodes by the procedure figure at a safe tip force."""
import json
import subprocess
import sys

from guidewire_nav import REPO_ROOT

SCRIPT = REPO_ROOT / "results" / "generalist" / "compare.py"


def episode(seed, outcome, tip_n):
    return {"anatomy": "a", "target": 1, "seed": seed, "outcome": "wrong_branch",
            "recovery": {"outcome": outcome, "force": {"peak_tip_N": tip_n}}}


def write(path, episodes):
    path.write_text(json.dumps({"rows": [{"name": "pool", "results": {"sac-policy": {"results": episodes}}}]}))
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
