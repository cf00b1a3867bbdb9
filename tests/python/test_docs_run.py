"""Every command the docs give runs (issue 65 item 1): each documented command (tests/python/docs_commands.py:
the command lines of the fenced blocks and command tables of README.md, docs/*.md and the folders' README.md
files that run one of the project's commands) runs in a short form and exits 0; test_docs_flags checks that
every flag it uses exists.

How a command runs:
- In a temporary folder of its block; a block's commands run in order there, so `plan --out runs/plan3` and
  then `navigate --replay runs/plan3/plan.json` works. `build/apps/NAME` is guidewire_nav.app_path(NAME)
  ($GW_BUILD_DIR), a console script or `python -m guidewire_nav.X` this test's Python (with the checkout's
  training/ first on PYTHONPATH), `python3 results/.../X.py` the checkout's script.
- Paths: what a command writes (the value of --out, --demos, --cache-dir, --regenerate, gw-cluster's --json,
  a `>` redirection) stays relative, so it lands in the temporary folder (its parent folder made first); any
  other relative path (a word with a `/` or a file extension) is one it reads: the temporary folder's if an
  earlier command of the block wrote it, else the checkout's. No file of the checkout changes: `git status
  --porcelain --untracked-files=all` is the same before and after.
- Short form: SHORT below, per command, sets flags (replacing the command's value, or adding the flag):
  navigate --episodes 1; evaluate (and gw-cluster) one row, --episode-scale 0.01 (a shard FIRST:COUNT:
  FIRST:1), --reachability-seeds 0, --threads 1; plan --budget 2000; gw-train --total-steps 64; the benchmarks
  their smallest runs. A command with --help runs as written.
- Exit 0, within 120 s (a timeout fails), and no silent failure (SILENT_FAILURES: evaluate exits 0 with a row
  it could not run marked "skipped" in its table). Two commands run at a time, Ray's (gw-cluster) one at a time.

Not run, each listed with its reason in the report the test prints (pytest -s, or on a failure):
- by rule: installing and building (`bash scripts/install.sh`, `bash scripts/test.sh`, `cmake`: what CI runs
  before the tests); `guidewire-server`, which serves until stopped (test_server_protocol drives it);
- placeholders, a synopsis or a pattern: a word with `[`, `]`, `|`, `...`, `$` or `<x>`; a word with a capital
  letter that names no file (FILE, N, DIR, arch_typeK.stl); a generic example file (GENERIC_FILES: actor.json,
  wire.json, vessels.stl, ...) that no earlier command of the block wrote;
- by the doc's markers, HTML comments on the lines right above the fenced block (or its table), each for all of
  the block's commands or, given "TEXT", for those containing TEXT (docs/commands.md's top says the same):
    <!-- docs-run: skip: REASON -->                  not run: needs a second machine, a Ray cluster, a GPU,
    <!-- docs-run: skip "TEXT": REASON -->           the network, hours or a person, or rewrites the checkout
    <!-- docs-run: record: WHEN -->                  a command as it ran at an earlier commit, its flags that
                                                     commit's: not run, flags not checked (test_docs_flags)
    <!-- docs-run: short: --flag V ... -->           set after SHORT's (replacing or adding)
    <!-- docs-run: sub: OLD => NEW; OLD2 => NEW2 --> text replaced before running (vessels.stl => a committed mesh)
A failure is one line: FILE:LINE, the exit code, the command as run, its last stderr line.
"""
import functools
import importlib.util
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import nullcontext
from pathlib import Path

import guidewire_nav
from conftest import app_or_skip
from docs_commands import APPS, REPO, SCRIPTS, commands_in, documented_commands, split_commands

TIMEOUT_S = 120
WORKERS = 2
MIN_RUN = 65  # fewer commands run means the scan or its rules broke (74 ran when this was set)

RULE_SKIPS = {
    "bash scripts/install.sh": "installs and builds (CI runs it before the tests)",
    "bash scripts/test.sh": "installs, builds and runs every test (what CI runs)",
    "cmake": "builds (CI builds before the tests)",
    "guidewire-server": "serves until stopped (test_server_protocol drives it)",
}
GENERIC_FILES = {"actor.json", "wire.json", "plan.json", "vessels.stl", "aorta.stl", "vessels_cl.vtp",
                 "observations", "repaired.stl"}
OUTPUT_FLAGS = {"--out", "--demos", "--cache-dir", "--regenerate"}
OUTPUT_FLAGS_OF = {"gw-cluster": {"--json"}}
PATH_LIKE = re.compile(r"/|\.[a-z][a-z0-9]*$")
REDIRECT = re.compile(r"\d?>>?|<")
# Output that fails a command that exited 0: evaluate's table line for a row it could not run.
SILENT_FAILURES = [re.compile(r"^- \*\*.*\*\*: skipped: .*$", re.M)]


def with_flag(args: list[str], flag: str, value, add: bool = True) -> list[str]:
    """args with flag's value replaced (value: a string, or a function of the old value, None when there is
    none), or flag and value appended where args lack the flag (and add)."""
    args = list(args)
    if flag in args:
        i = args.index(flag)
        old = args[i + 1] if i + 1 < len(args) and not args[i + 1].startswith("--") else None
        args[i + 1:i + 1 + (old is not None)] = [value(old) if callable(value) else value]
    elif add:
        args += [flag, value(None) if callable(value) else value]
    return args


def with_flags(args: list[str], values: dict) -> list[str]:
    for flag, value in values.items():
        args = with_flag(args, flag, value)
    return args


@functools.cache
def first_row(rows: str) -> str:
    """The name of the first row of evaluate's table that --rows ROWS selects (`evaluate --plan`), so that the
    short form runs one row where the text matches several (`coronary`: four)."""
    plan = subprocess.run([str(guidewire_nav.app_path("evaluate")), "--plan", "--rows", rows],
                          capture_output=True, text=True, timeout=60)
    names = [row["name"] for row in json.loads(plan.stdout)["rows"]] if plan.returncode == 0 else []
    return names[0] if names else rows.split(",")[0]


def evaluate_short(args: list[str]) -> list[str]:
    """evaluate's (and gw-cluster's) short form: its first row, 1% of the episodes (a shard FIRST:COUNT runs
    FIRST:1), no reachability probe, one thread, a small planner budget. --from-json and --plan run nothing
    and stay as they are."""
    if "--from-json" in args or "--plan" in args:
        return args
    args = with_flag(args, "--rows", lambda rows: first_row(rows or "coronary-like"))
    if "--episodes" in args:
        args = with_flag(args, "--episodes", lambda shard: f"{shard.split(':')[0]}:1")
    else:
        args = with_flag(args, "--episode-scale", "0.01")
    args = with_flags(args, {"--reachability-seeds": "0", "--threads": "1"})
    return with_flag(with_flag(args, "--planned-seeds", "1", add=False), "--plan-budget", "200", add=False)


def navigate_short(args: list[str]) -> list[str]:
    if "--target" in args or "--target-point" in args:
        args = with_flag(args, "--episodes", "1")
    return with_flag(args, "--threads", "1")


# The short form per command (its --help name): args -> args. A documented command without a row runs as
# written; one that runs long needs a row here (or a `short` marker in its doc).
SHORT = {
    "navigate": navigate_short,
    "plan": lambda a: with_flag(a, "--budget", "2000"),
    "evaluate": evaluate_short,
    "gw-cluster evaluate": lambda a: with_flag(evaluate_short(a), "--cpus", "2"),
    "gw-cluster bench": lambda a: with_flag(evaluate_short(a), "--cpus", "2"),
    "gw-train": lambda a: with_flags(a, {"--total-steps": "64", "--learning-starts": "32", "--envs": "1",
                                         "--eval-episodes": "0", "--max-minutes": "2", "--torch-threads": "1"}),
    "gw-segmentation-set": lambda a: with_flag(a, "--only", "rca_plain"),
    "bench-env": lambda a: with_flag(a, "--steps", "20"),
    "bench-centerline": lambda a: with_flags(a, {"--only": "t1_straight_y", "--repeat": "1"}),
    "bench-policy": lambda a: with_flag(a, "--calls", "100"),
}


def substituted(doc) -> str:
    text = doc.text
    for value in doc.marked("sub"):
        for pair in value.split(";"):
            old, _, new = pair.partition("=>")
            text = text.replace(old.strip(), new.strip())
    return text


def skip_reason(doc) -> str | None:
    """Why a command is not run, from its markers and the rules (before its words are read)."""
    if reasons := doc.marked("skip"):
        return f"marked: {reasons[0]}"
    if whens := doc.marked("record"):
        return f"record: {whens[0]}"
    if doc.name in RULE_SKIPS:
        return f"rule: {RULE_SKIPS[doc.name]}"
    if doc.name == "gw-cluster" and importlib.util.find_spec("ray") is None:
        return "rule: Ray is not installed (the [cluster] extra)"
    return None


def placeholder(words: list[str], cwd: Path) -> str | None:
    """The first word that shows a command is a synopsis or a pattern, not a command; None if none does."""
    for word in words:
        names_a_file = (cwd / word).exists() or (REPO / word).exists()
        if (any(s in word for s in ("[", "]", "|", "...", "$")) or re.search(r"<\w[^>]*>", word)
                or (re.search(r"[A-Z]", word) and not names_a_file)
                or (word in GENERIC_FILES and not (cwd / word).exists())):
            return word
    return None


def program_argv(doc, words: list[str]) -> list[str]:
    """The argv that runs the program a command's first words name."""
    if doc.name in APPS:
        return [str(guidewire_nav.app_path(doc.name))]
    if doc.name in SCRIPTS:
        module, _, func = SCRIPTS[doc.name].partition(":")
        return [sys.executable, "-c", f"import sys; from {module} import {func}; sys.argv[0] = {doc.name!r}; {func}()"]
    if doc.name.startswith("python -m "):
        return [sys.executable, "-m", doc.name.split()[-1]]
    assert doc.name.startswith("python3 "), f"{doc.where}: no way to run {doc.name}"
    return [sys.executable, str(REPO / words[-1])]


def resolved(doc, args: list[str], cwd: Path) -> list[str]:
    """args with the outputs left relative (their parent folder made in cwd), the inputs made absolute (cwd's
    where an earlier command wrote them, else the checkout's) and `build/apps/NAME` the built app."""
    outputs = OUTPUT_FLAGS | OUTPUT_FLAGS_OF.get(doc.name, set())
    out = []
    for i, word in enumerate(args):
        before = args[i - 1] if i else ""
        if before in outputs or REDIRECT.fullmatch(before) and before != "<":
            (cwd / word).parent.mkdir(parents=True, exist_ok=True)
        elif app := re.fullmatch(r"(?:\S*/)?build/apps/([\w-]+)", word):
            word = str(guidewire_nav.app_path(app.group(1)))
        elif (PATH_LIKE.search(word) and not word.startswith("-") and not (cwd / word).exists()
              and (REPO / word).exists()):
            word = str(REPO / word)
        out.append(word)
    return out


def shell_command(doc, cwd: Path) -> tuple[str | None, str | None]:
    """(the shell command that runs a command's short form in cwd, None), or (None, why it is not run)."""
    if reason := skip_reason(doc):
        return None, reason
    try:
        words = shlex.split(substituted(doc))
    except ValueError:
        return None, "placeholder: not shell words"
    if word := placeholder(words[doc.prefix:], cwd):
        return None, f"placeholder: {word}"
    args = words[doc.prefix:]
    cut = next((i for i, w in enumerate(args) if REDIRECT.fullmatch(w)), len(args))
    args, redirects = args[:cut], args[cut:]
    if "--help" not in args:
        args = SHORT.get(doc.command, lambda a: a)(args)
        for flags in map(shlex.split, doc.marked("short")):
            args = with_flags(args, dict(zip(flags[::2], flags[1::2])))
    argv = program_argv(doc, words[:doc.prefix]) + resolved(doc, args + redirects, cwd)
    command, tail = argv[:len(argv) - len(redirects)], argv[len(argv) - len(redirects):]
    return shlex.join(command) + "".join(f" {w}" if REDIRECT.fullmatch(w) else f" {shlex.quote(w)}" for w in tail), None


RAY = threading.Lock()  # one local Ray at a time


def run_one(doc, shell: str, cwd: Path) -> tuple[int | str, str]:
    """(exit code, 'timeout' or 'silent failure', and the line that says why) of one command."""
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1",
               PYTHONPATH=os.pathsep.join(filter(None, [str(REPO / "training"), os.environ.get("PYTHONPATH")])))
    with RAY if doc.name == "gw-cluster" else nullcontext():
        proc = subprocess.Popen(["bash", "-c", shell], cwd=cwd, env=env, stdin=subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            out, err = proc.communicate(timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            out, err = proc.communicate()
            return f"timeout ({TIMEOUT_S} s)", _last_line(err)
    if proc.returncode == 0:
        silent = [m.group(0) for pattern in SILENT_FAILURES for m in pattern.finditer(out + err)]
        return (0, "") if not silent else ("0, a silent failure", silent[0])
    return proc.returncode, _last_line(err)


def _last_line(text: str) -> str:
    lines = [ln for ln in text.splitlines() if ln.strip()]
    return lines[-1] if lines else ""


def run_unit(docs, cwd: Path) -> list[tuple]:
    """[(doc, reason it was not run or None, failure line or None, seconds)] of one block's commands, run in
    order in cwd."""
    cwd.mkdir(parents=True)
    done = []
    for doc in docs:
        shell, reason = shell_command(doc, cwd)
        if shell is None:
            done.append((doc, reason, None, 0.0))
            continue
        start = time.monotonic()
        code, why = run_one(doc, shell, cwd)
        failure = None if code == 0 else f"{doc.where}: exit {code}: {shell}: {why}"
        done.append((doc, None, failure, time.monotonic() - start))
    return done


def git_status() -> str:
    return subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=REPO,
                          capture_output=True, text=True, check=True).stdout


def report(ran, not_run, wall_s: float) -> str:
    failed = sum(1 for r in ran if r[2])
    lines = [f"docs run: {len(ran)} documented commands ran ({failed} failed) in {wall_s:.0f} s, "
             f"{len(not_run)} not run:"]
    lines += [f"  {doc.where}: {doc.text[:60]}: {reason}" for doc, reason, _, _ in not_run]
    lines += [f"  slowest: {doc.where}: {s:.0f} s" for doc, _, _, s in sorted(ran, key=lambda r: -r[3])[:5]]
    return "\n".join(lines)


def test_every_documented_command_runs(tmp_path, capsys):
    for name in APPS:
        app_or_skip(name)
    units = {}
    for doc in documented_commands():
        units.setdefault(doc.unit, []).append(doc)
    before = git_status()
    start = time.monotonic()
    with ThreadPoolExecutor(WORKERS) as pool:
        done = pool.map(lambda unit: run_unit(units[unit], tmp_path / re.sub(r"\W", "_", unit)), units)
        results = [r for unit in done for r in unit]
    ran = [r for r in results if r[1] is None]
    not_run = [r for r in results if r[1] is not None]
    with capsys.disabled():
        print("\n" + report(ran, not_run, time.monotonic() - start))
    assert git_status() == before, "the documented commands changed the checkout:\n" + git_status()
    failures = [r[2] for r in ran if r[2]]
    assert not failures, "documented commands that fail:\n" + "\n".join(failures)
    assert len(ran) >= MIN_RUN, \
        f"only {len(ran)} documented commands ran (floor {MIN_RUN}): the scan or its rules broke"


def test_split_and_table_rules():
    """A synopsis's `|` inside brackets is no pipe; a table is a command table when its header says so."""
    assert split_commands("a [--x N | --y] && b; c | d  # e; f") == ["a [--x N | --y]", "b", "c", "d"]
    assert split_commands("a > ${x}_<alone|assist>.json | b") == ["a > ${x}_<alone|assist>.json", "b"]
    doc = ("| command | does |\n|---|---|\n| `evaluate --out results` | x |\n\n"
           "| folder | uses |\n|---|---|\n| `plan` | x |\n")
    assert [c.text for c in commands_in(Path("d.md"), doc)] == ["evaluate --out results"]


def test_short_forms():
    assert with_flag(["--episodes", "50", "--json"], "--episodes", "1") == ["--episodes", "1", "--json"]
    assert with_flag(["--json"], "--episodes", "1") == ["--json", "--episodes", "1"]
    assert with_flag(["--json"], "--plan-budget", "200", add=False) == ["--json"]
    app_or_skip("evaluate")
    assert first_row("coronary") == "coronary-like"  # the first of the four rows `coronary` selects
    short = evaluate_short(["--rows", "deformed", "--episodes", "25:25", "--threads", "2"])
    assert short == ["--rows", "deformed coronary", "--episodes", "25:1", "--threads", "1", "--reachability-seeds", "0"]
    assert evaluate_short(["--from-json", "a/results.json"]) == ["--from-json", "a/results.json"]


T1 = "anatomies/train/t1_straight_y/t1_straight_y.stl"
SAMPLE = f"""
<!-- docs-run: sub: vessels.stl => {T1} -->
```bash
build/apps/plan --anatomy vessels.stl --target 2 --out runs/p              # writes runs/p/plan.json
build/apps/navigate --anatomy vessels.stl --replay runs/p/plan.json --json > runs/replay.json
build/apps/evaluate --policy runs/none/actor.json --rows coronary-like      # a row it cannot run
navigate --anatomy FILE [--json]
```
<!-- docs-run: skip "--list": a reason -->
<!-- docs-run: short: --seed 4 -->
```
build/apps/navigate --anatomy {T1} --list
build/apps/navigate --anatomy {T1} --target 1 --episodes 30 --out runs/n
```
"""


def test_the_runner_on_a_sample_doc(tmp_path):
    """A block's commands run in order in its folder (the replay reads the plan the line above wrote; the
    redirection writes there); a failing command is reported; placeholders and markers skip; short forms apply."""
    for name in ("plan", "navigate", "evaluate"):
        app_or_skip(name)
    docs = commands_in(Path("sample.md"), SAMPLE)
    first = run_unit([d for d in docs if d.unit == docs[0].unit], tmp_path / "a")
    assert [r[1] for r in first] == [None, None, None, "placeholder: FILE"]
    assert first[0][2] is None and first[1][2] is None, first
    assert json.loads((tmp_path / "a/runs/replay.json").read_text())
    # a missing actor: evaluate refuses it up front (exit 1, naming it); before, a silent "skipped" row
    assert "exit 1" in first[2][2] and "runs/none/actor.json" in first[2][2]
    second = run_unit([d for d in docs if d.unit != docs[0].unit], tmp_path / "b")
    assert [r[1] for r in second] == ["marked: a reason", None] and second[1][2] is None
    shell, _ = shell_command(docs[-1], tmp_path / "b")
    assert "--episodes 1" in shell and "--seed 4" in shell and str(REPO / T1) in shell and "runs/n" in shell
    assert (tmp_path / "b/runs/n/episode0_target1.json").is_file()
