"""The layers of docs/architecture.md, enforced. The "Include direction" table there is read as it is:
every quoted `#include` of every C++ source outside tests/ is resolved to the file it names (a bare
name in the including file's own folder, else a path from the repository root) and the folder of that
file must be the including folder or one its table row lists. The table must name exactly the
folders that hold sources and exactly what each reaches (a dependency nobody uses is not allowed
either), its rows must go down the layers (no cycle, no top-level folder reaching one above it), and
CGAL stays inside the .cpp files of the extraction and the generator.

A new dependency is a design change: edit the table in docs/architecture.md first."""
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SOURCE_TOPS = ("base", "engine", "task", "plan", "centerline", "anatomy_gen", "policy", "lib", "apps")
# The picture of docs/architecture.md, lowest first: a folder may reach only its own or lower ranks.
RANK = {"base": 0, "engine": 1, "task": 2, "plan": 3, "centerline": 3, "anatomy_gen": 3, "policy": 3, "lib": 4, "apps": 5}
CGAL_FOLDERS = ("centerline", "anatomy_gen")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
CGAL = re.compile(r"^\s*#\s*include\s+<CGAL/", re.M)
ROW = re.compile(r"^\|\s*`([^`]+)`\s*\|(.*)\|\s*$")


def read_table(doc=None):
    """{folder: set of folders it may include} from the table under "## Include direction"."""
    text = (doc or REPO / "docs" / "architecture.md").read_text()
    section = text.split("## Include direction", 1)[1].split("\n## ", 1)[0]
    table = {}
    for line in section.splitlines():
        m = ROW.match(line.strip())
        if m:
            table[m.group(1)] = set(re.findall(r"`([^`]+)`", m.group(2)))
    assert table, "docs/architecture.md: no include table under '## Include direction'"
    return table


def sources(repo):
    for top in SOURCE_TOPS:
        for p in sorted((repo / top).rglob("*")):
            if p.suffix in (".hpp", ".cpp", ".h") and p.is_file():
                yield p


def folder_of(path, repo):
    return path.parent.relative_to(repo).as_posix()


def reached(repo):
    """{folder: {folder it includes: [example include]}} and the includes that resolve to no file."""
    reach, unresolved = {}, []
    for p in sources(repo):
        own = folder_of(p, repo)
        reach.setdefault(own, {})
        for target in INCLUDE.findall(p.read_text(errors="replace")):
            hit = next((c for c in (p.parent / target, repo / target) if c.is_file()), None)
            if hit is None:
                unresolved.append(f"{p.relative_to(repo)}: #include \"{target}\"")
                continue
            other = folder_of(hit.resolve(), repo.resolve())
            if other != own:
                reach[own].setdefault(other, f"{p.relative_to(repo)} includes {target}")
    return reach, unresolved


def check(repo=REPO, doc=None):
    table = read_table(doc)
    reach, unresolved = reached(repo)
    problems = [f"unresolved include (not a file of ours): {u}" for u in unresolved]
    problems += [f"{f}: a folder with sources and no row in the table" for f in sorted(set(reach) - set(table))]
    problems += [f"{f}: a table row for a folder with no sources" for f in sorted(set(table) - set(reach))]
    for own, targets in sorted(reach.items()):
        allowed = table.get(own, set())
        if own == "apps":
            continue  # "any folder above"
        for other, example in sorted(targets.items()):
            if other not in allowed:
                problems.append(f"{example} ({own} may not use {other})")
        for unused in sorted(allowed - set(targets)):
            problems.append(f"{own}: the table allows {unused}, which no include of {own} uses")
    return problems


def test_includes_match_the_table_exactly():
    problems = check()
    assert not problems, "includes against docs/architecture.md's table:\n" + "\n".join(problems)


def test_the_table_goes_down_the_layers():
    table = read_table()
    bad = [f"{f} -> {t}" for f, ts in table.items() for t in ts - {"any folder above"}
           if RANK[t.split("/")[0]] > RANK[f.split("/")[0]]]
    assert not bad, "table rows reaching a higher layer: " + ", ".join(bad)
    # no cycle among folders (the engine's and lib's sub-folders rank among themselves this way)
    seen, done = set(), set()

    def visit(f, path):
        assert f not in seen or f in done, "include cycle: " + " -> ".join(path + [f])
        if f in done:
            return
        seen.add(f)
        for t in table.get(f, set()) - {"any folder above"}:
            visit(t, path + [f])
        done.add(f)

    for f in table:
        visit(f, [])


def test_cgal_stays_in_the_extraction_and_generator_sources():
    bad = [str(p.relative_to(REPO)) for p in sources(REPO) if CGAL.search(p.read_text(errors="replace"))
           and not (p.suffix == ".cpp" and folder_of(p, REPO).split("/")[0] in CGAL_FOLDERS)]
    assert not bad, "CGAL included outside centerline/ and anatomy_gen/ .cpp files: " + ", ".join(bad)


def test_the_check_sees_a_violation(tmp_path):
    """The scan itself works: an engine header that includes the task, a two-part include
    included, is reported; so are an unresolved include and a stale table row."""
    doc = tmp_path / "architecture.md"
    doc.write_text("## Include direction\n| folder | may include |\n|---|---|\n"
                   "| `engine/sim` | nothing |\n| `task` | `engine/sim` |\n| `policy` | nothing |\n")
    (tmp_path / "engine" / "sim").mkdir(parents=True)
    (tmp_path / "task").mkdir()
    (tmp_path / "task" / "episode.hpp").write_text("#pragma once\n")
    (tmp_path / "engine" / "sim" / "bad.hpp").write_text('#pragma once\n#include "task/episode.hpp"\n#include "nowhere.hpp"\n')
    problems = "\n".join(check(tmp_path, doc))
    assert "engine/sim may not use task" in problems
    assert 'unresolved include (not a file of ours): engine/sim/bad.hpp: #include "nowhere.hpp"' in problems
    assert "task: the table allows engine/sim, which no include of task uses" in problems
    assert "policy: a table row for a folder with no sources" in problems
