"""The `evaluate` app: progress with an ETA on stderr, results.json rewritten after every row, and
--resume keeping the rows an interrupted or shorter run finished, so that the table ends equal to an
uninterrupted run's (episode k of a row has seed S+k: same seed, same episodes).

A tiny table: the three sensitivity var rows, one push-only episode each, ground-truth centerlines, no
reachability probes."""

import json
import signal
import subprocess
import time
from pathlib import Path

import pytest

import guidewire_nav

REPO = Path(__file__).resolve().parents[2]
TINY = ["--controllers", "push-only", "--centerlines", "truth", "--episode-scale", "0.02", "--reachability-seeds", "0",
        "--threads", "1"]
ROWS = ["sensitivity: var1", "sensitivity: var2", "sensitivity: var3"]


@pytest.fixture(scope="module")
def evaluate():
    path = guidewire_nav.app_path("evaluate")
    if not path.is_file():
        pytest.skip(f"evaluate not built ({path}); set GW_BUILD_DIR")
    return path


def command(evaluate, out: Path, *extra: str, rows: str = "var", seed: int = 7) -> list[str]:
    return [str(evaluate), "--out", str(out), *TINY, "--rows", rows, "--seed", str(seed), *extra]


def run(evaluate, out: Path, *extra: str, **kwargs) -> subprocess.CompletedProcess:
    done = subprocess.run(command(evaluate, out, *extra, **kwargs), capture_output=True, text=True, cwd=REPO,
                          timeout=1200)
    assert done.returncode == 0, done.stderr
    return done


def table(out: Path) -> dict:
    """results.json without the rows' wall times (the only field two equal runs differ in)."""
    result = json.loads((out / "results.json").read_text())
    for row in result["rows"]:
        row.pop("wall_time_s")
    return result


@pytest.fixture(scope="module")
def uninterrupted(evaluate, tmp_path_factory):
    out = tmp_path_factory.mktemp("full")
    done = run(evaluate, out)
    return out, done


def test_progress_has_an_eta_and_a_line_per_row(uninterrupted):
    out, done = uninterrupted
    assert [r["name"] for r in table(out)["rows"]] == ROWS
    assert all(r["results"]["push-only"]["episodes"] == 1 for r in table(out)["rows"])
    for k, name in enumerate(ROWS, 1):
        assert f"row {k}/3 {name} done in" in done.stderr
    assert "3/3 episodes" in done.stderr and "ETA" in done.stderr
    assert "| sensitivity: var3 |" in done.stdout  # the Markdown table on stdout, as before
    assert (out / "results.md").read_text() == done.stdout


def test_resume_after_a_shorter_run_keeps_its_rows_and_equals_the_full_run(evaluate, uninterrupted, tmp_path):
    run(evaluate, tmp_path, rows="var1")  # limited: one row finished
    first = json.loads((tmp_path / "results.json").read_text())
    assert [r["name"] for r in first["rows"]] == ROWS[:1]
    done = run(evaluate, tmp_path, "--resume")
    assert "1 finished row(s)" in done.stderr
    assert f"row 1/3 {ROWS[0]}: kept from the earlier run" in done.stderr
    assert f"{ROWS[0]} done in" not in done.stderr  # not run again
    assert "2/2 episodes" in done.stderr  # only the two other rows' episodes were counted and run
    resumed = json.loads((tmp_path / "results.json").read_text())
    assert resumed["rows"][0]["wall_time_s"] == first["rows"][0]["wall_time_s"]
    assert table(tmp_path) == table(uninterrupted[0])
    assert (tmp_path / "results.md").read_text() == (uninterrupted[0] / "results.md").read_text()


def test_an_interrupted_run_keeps_its_finished_rows_and_resumes_to_the_same_table(evaluate, uninterrupted, tmp_path):
    proc = subprocess.Popen(command(evaluate, tmp_path), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            cwd=REPO)
    results = tmp_path / "results.json"
    while proc.poll() is None and not results.exists():  # the first row is written as soon as it is finished
        time.sleep(0.02)
    proc.send_signal(signal.SIGTERM)
    proc.communicate(timeout=600)
    assert proc.returncode in (0, -signal.SIGTERM)  # 0: it finished before the signal (rows take seconds)
    written = json.loads(results.read_text())  # whole, never half a file (written atomically)
    assert written["rows"]  # results.json appears when a row is finished, never with none (at most 3: the next line)
    assert [r["name"] for r in written["rows"]] == ROWS[:len(written["rows"])]
    done = run(evaluate, tmp_path, "--resume")
    assert f"{len(written['rows'])} finished row(s)" in done.stderr
    assert table(tmp_path) == table(uninterrupted[0])


def test_resume_refuses_other_settings(evaluate, uninterrupted, tmp_path):
    run(evaluate, tmp_path, rows="var1")
    done = subprocess.run(command(evaluate, tmp_path, "--resume", seed=8), capture_output=True, text=True, cwd=REPO,
                          timeout=600)
    assert done.returncode == 1
    assert "--resume: the earlier run's seed was 7, this run's is 8" in done.stderr
