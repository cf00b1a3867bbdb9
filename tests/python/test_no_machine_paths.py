"""No tracked file names a folder of the machine it was made on (issue 61, item 6).

Results, shipped actors, scripts and docs record paths relative to the repository root (evaluate and
navigate do so themselves: `recorded_path` in lib/runner); a run's own scratch output goes under the
ignored runs/ or .cache/. What counts as a machine path: an absolute path whose first folder is one of
MACHINE_ROOTS (home and scratch folders, mounts, the folder this project was first run in), or a Windows
user folder. System paths are not machine paths and are not matched: /usr/bin/env in a shebang,
/dev/null, /proc, /usr/include, /bin/bash. A path inside a URL (https://host/home/...) or after a
variable ($HOME/tmp, ${DIR}/data) is not absolute and is not matched either.

A file that must name such a folder goes in ALLOWED with the exact text and the reason.
"""
import re
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

MACHINE_ROOTS = ("home", "root", "tmp", "work", "workspace", "Users", "mnt", "media", "scratch", "srv", "opt",
                 "var", "private", "data", "nfs", "gpfs", "lustre", "net", "cluster")
# Not preceded by a name, a dot, ~, -, a slash, a backslash or a variable's end (a relative or URL path);
# the root folder then ends the path or goes on with "/".
PATTERN = re.compile(r"(?<![\w.~\-/\\$})\]])/(?:" + "|".join(MACHINE_ROOTS) + r")(?=/|[\s\"'`),;:]|\.(?:[\s\"'`)]|$)|$)"
                     r"|\b[A-Za-z]:[\\/]+(?:Users|home)\b")

S = "/"  # the paths in this file are built from S, so that it names no machine path itself

# (path, exact text on the line, reason). Each entry must still match (test_allow_list_is_used).
ALLOWED = [
    ("docs/cluster.md", f"else in `{S}tmp`.",
     "says where a Ray task runs on a node without the checkout, not a path this project ran in"),
    ("training/guidewire_nav/cluster.py", f"else {S}tmp.",
     "run_shard's docstring, the same statement as docs/cluster.md"),
]


def machine_paths(text: str) -> list[re.Match]:
    return list(PATTERN.finditer(text))


def tracked_text_files() -> dict[str, str]:
    try:
        listed = subprocess.run(["git", "ls-files", "-z"], cwd=REPO, capture_output=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        pytest.skip(f"not a git checkout ({e}): nothing to list")
    files = {}
    for name in listed.decode().split("\0"):
        path = REPO / name
        if not name or not path.is_file():  # a deletion not yet committed
            continue
        data = path.read_bytes()
        if b"\0" in data[:8192]:  # binary: PNG, STL, zip
            continue
        try:
            files[name] = data.decode("utf-8")
        except UnicodeDecodeError:
            continue
    return files


def findings(files: dict[str, str]) -> tuple[list[str], set[int]]:
    """'file:line: ...text...' for each machine path not allowed, and the indices of the ALLOWED entries used."""
    found, used = [], set()
    for name, text in files.items():
        for number, line in enumerate(text.splitlines(), 1):
            for m in machine_paths(line):
                allowed = [i for i, (path, exact, _) in enumerate(ALLOWED) if path == name and exact in line
                           and line.index(exact) <= m.start() < line.index(exact) + len(exact)]
                if allowed:
                    used.update(allowed)
                    continue
                found.append(f"{name}:{number}: ...{line[max(0, m.start() - 60):m.end() + 60]}...")
    return found, used


def test_no_tracked_file_names_a_machine_path():
    found, _ = findings(tracked_text_files())
    assert not found, ("tracked files name folders of the machine they were made on (record paths relative to "
                       "the repository root, or add to ALLOWED with a reason):\n" + "\n".join(found))


def test_allow_list_is_used():
    _, used = findings(tracked_text_files())
    stale = [ALLOWED[i][:2] for i in range(len(ALLOWED)) if i not in used]
    assert not stale, f"ALLOWED entries that no longer match anything (remove them): {stale}"


@pytest.mark.parametrize("line", [
    f'"out": "{S}work/runs/obs3_reach",',
    f'"policy": "{S}tmp/pp50k.json",',
    f"    python3 -m venv {S}tmp/vtkvenv && ...",
    f"--out={S}home/someone/runs/x",
    f"cd {S}root && make",
    f'real = Path("{S}scratch/vmtkrun/t1_vmtk.vtp")',
    f"Wire parameters from {S}mnt/shared/wire.json (the",
    f"C:{S}Users{S}someone{S}wire.json",
    "C:" "\\Users\\someone\\wire.json",
    f"written to {S}tmp.",
])
def test_machine_paths_are_found(line):
    assert machine_paths(line), line


@pytest.mark.parametrize("line", [
    "#!/usr/bin/env python3",
    "build/apps/evaluate --out results/push_pull > /dev/null",
    "cat /proc/cpuinfo",
    "#include </usr/include/stdio.h>",
    "see https://example.org/home/tmp/index.html",
    f"ln -s $HOME{S}tmp x; cp ${{DIR}}{S}data/x .",
    'std::string(GW_SOURCE_DIR) + "/tests/data/" + relative',
    "results/junctions/separate_outer_25_49/results.json",
    "runs/obs3_reach/scored/ckpt_90000.json",
    "obs/3 and act/2, mm/s, and/or, w/opt",
    "a file in ~/work/x is the user's, not absolute",
    f"{S}workshop/x and {S}homework are other folders",
])
def test_other_paths_are_not(line):
    assert not machine_paths(line), line
