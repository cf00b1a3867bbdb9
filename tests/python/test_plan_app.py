"""The `plan` app end to end on a training Y: it writes plan.json, the replayed episode's files and the
demonstrations, and `navigate --replay` retraces the plan to the same end, step for step."""
import json
import subprocess
from pathlib import Path

from conftest import app_or_skip as app

REPO = Path(__file__).resolve().parents[2]
T1 = str(REPO / "anatomies/train/t1_straight_y/t1_straight_y.stl")



def test_plan_writes_a_replayable_plan_and_demonstrations(tmp_path):
    out, demos = tmp_path / "plan", tmp_path / "demos.jsonl"
    r = subprocess.run([app("plan"), "--anatomy", T1, "--target", "2", "--seed", "4", "--out", str(out),
                        "--demos", str(demos), "--json"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    plan = json.loads((out / "plan.json").read_text())
    assert plan == json.loads(r.stdout)
    assert plan["format"] == "guidewire-nav/plan/1" and plan["reached"] and plan["found"] in ("strict", "procedure")
    assert plan["target"] == 2 and plan["seed"] == 4 and plan["task"]["action"] == "guidewire-nav/act/2"
    assert plan["peak_tip_force_N"] <= plan["force_limit_N"]
    assert (out / "target2.png").is_file() and (out / "episode0_target2.json").is_file()
    lines = [json.loads(x) for x in demos.read_text().splitlines()]
    assert [d["action"] for d in lines] == plan["actions"]  # one pair per step in control, in order
    assert plan["task"]["observation"]["tip_force"]  # obs/8, the generalist's layout: obs/5 and the tip force
    assert all(len(d["obs"]) == 15 and 0.0 <= d["obs"][14] for d in lines)

    r = subprocess.run([app("navigate"), "--anatomy", T1, "--replay", str(out / "plan.json"), "--json"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    episode = summary["results"][0]
    assert summary["controller"] == "replay" and episode["target"] == 2 and episode["seed"] == 4
    assert episode["recovery"]["outcome"] == "success" and episode["recovery"]["steps"] == plan["steps"]
    assert episode["recovery"]["attempts"] == plan["wrong_entries"]
    assert abs(episode["recovery"]["force"]["peak_tip_N"] - plan["peak_tip_force_N"]) < 1e-12

    r = subprocess.run([app("navigate"), "--anatomy", T1, "--replay", str(out / "plan.json"), "--controller", "push-only"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode != 0 and "--replay" in r.stderr.strip().splitlines()[-1]


def test_plan_from_a_lead_in_writes_only_the_search_steps_as_demonstrations(tmp_path):
    # The shipped actor reaches target 2 of this Y: its episode is the plan, nothing to relabel. An actor that only
    # pulls gets no deeper than its start: the search starts at the reset, and every step is the search's.
    actor = str(REPO / "policy/trained/sac_actor.json")
    out, demos = tmp_path / "plan", tmp_path / "demos.jsonl"
    r = subprocess.run([app("plan"), "--anatomy", T1, "--target", "2", "--seed", "4", "--lead-in", actor,
                        "--demos", str(demos), "--json"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    plan = json.loads(r.stdout)
    lead = plan["lead_in"]
    assert lead["outcome"] == "success" and lead["steps"] == lead["ran"] == plan["steps"]
    assert plan["guide"].endswith("sac_actor.json") and plan["search"]["strict"]["maneuvers"] == 0
    assert demos.read_text() == ""

    from guidewire_nav.export_actor import widen_to_push_pull
    d = widen_to_push_pull(json.loads(Path(actor).read_text()), insertion_bias=-3.0)  # pulls at tanh(-3)
    last = d["layers"][-1]
    last["weight"] = [0.0] * len(last["weight"])
    last["bias"][0] = 0.0  # and turns not at all
    puller = tmp_path / "puller.json"
    puller.write_text(json.dumps(d))
    r = subprocess.run([app("plan"), "--anatomy", T1, "--target", "2", "--seed", "4", "--lead-in", str(puller),
                        "--out", str(out), "--demos", str(demos), "--json"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    plan = json.loads(r.stdout)
    lead = plan["lead_in"]
    assert lead["outcome"] != "success" and lead["deepest_step"] == 0 and lead["steps"] == 0
    lines = [json.loads(x) for x in demos.read_text().splitlines()]
    assert [d["action"] for d in lines] == plan["actions"][lead["steps"]:] != []  # the search's steps
    r = subprocess.run([app("navigate"), "--anatomy", T1, "--replay", str(out / "plan.json"), "--json"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["results"][0]["recovery"]["steps"] == plan["steps"]  # from the reset, retraced
