"""Every relative link of every tracked Markdown file resolves: `[text](path)` names a file or folder that
exists relative to the file that links it (anchors and web addresses are not checked). A moved folder
or a renamed result that leaves a link behind fails here."""
import re
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LINK = re.compile(r"\]\(([^)#\s]+)(#[^)]*)?\)")


def broken_links(repo=REPO):
    files = subprocess.run(["git", "ls-files", "*.md"], cwd=repo, capture_output=True, text=True, check=True).stdout.split()
    bad = []
    for name in files:
        path = repo / name
        if not path.is_file():
            continue
        for m in LINK.finditer(path.read_text(errors="replace")):
            target = m.group(1)
            if re.match(r"[a-z][a-z0-9+.-]*:", target):  # https:, mailto:
                continue
            if not (path.parent / target).exists():
                bad.append(f"{name}: ({target})")
    return bad


def test_every_relative_markdown_link_resolves():
    bad = broken_links()
    assert not bad, "links to nothing:\n" + "\n".join(bad)


def test_the_check_sees_a_broken_link(tmp_path):
    subprocess.run(["git", "init", "-q"], cwd=tmp_path, check=True)
    (tmp_path / "a.md").write_text("[ok](a.md) [web](https://example.org) [gone](missing/file.json#x)\n")
    subprocess.run(["git", "add", "a.md"], cwd=tmp_path, check=True)
    assert broken_links(tmp_path) == ["a.md: (missing/file.json)"]
