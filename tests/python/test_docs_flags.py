"""docs/commands.md documents every flag of every command, and no flag a command lacks (issue 65 item 2).

The commands: every C++ executable apps/CMakeLists.txt declares (`gw_add_app(NAME ...)`, run from
$GW_BUILD_DIR/apps, guidewire_nav.app_path) and every console script of training/pyproject.toml's
[project.scripts] (its entry point, as test_packaging runs it), with an argparse sub-command (`gw-cluster
evaluate`) a command of its own. A command's flags are the long flags its `--help` lists as options (the
option column only: a flag its help text merely mentions, like CLI11's "Excludes: --target-point", is not
one), `--help` itself excluded.

The convention in docs/commands.md, which this test enforces:
- Each command has one heading (any level) whose text starts with its name, e.g. "## navigate (the main job)",
  "### gw-cluster evaluate". Its section runs to the next heading of the same or a higher level, or to the
  next heading of another command (so `gw-cluster`'s stops at `gw-cluster evaluate`'s sub-heading).
- The flags the doc gives a command are every `--flag` written in its section (synopsis block, prose,
  tables), except those in a code span or a code-block line that starts with another command's name
  (`guidewire-server --step-cutoff S` inside navigate's section documents guidewire-server, not navigate).
- The flags lib/runner/task_options.cpp declares once for navigate, evaluate and guidewire-server
  (TASK_OPTION_APPS) are documented once, in the section headed "Task options"; it counts for each of
  those three.
- A group of a command's --help titled "OTHER's flags ..." (gw-cluster's "evaluate's flags (`evaluate --help`),
  passed to every shard unchanged") holds another command's flags, passed on: they are OTHER's, documented in
  OTHER's section (the command's own may name them too), and must all be in OTHER's --help.
A flag the help lists that the command's sections do not name fails, and so does a flag they name that the
help does not list; each failure names the command and the flag.
"""
import re
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import pytest

import guidewire_nav
from docs_commands import APPS, REPO, SCRIPTS, documented_commands

DOC = REPO / "docs" / "commands.md"

# Commands whose --help takes the shared task flags (gw::add_task_options), documented under "Task options".
TASK_OPTION_APPS = ("navigate", "evaluate", "guidewire-server")
TASK_OPTIONS_HEADING = "Task options"

# Flags a command has that its doc section may leave out, or the reverse, with the reason. Keep it short.
ALLOWED = {
    # (command, flag): reason
}

EXCLUDED = {"--help"}


def option_flags(help_text: str) -> set[str]:
    """The long flags the option column of a CLI11 or argparse --help lists.

    An option line is indented by at most 4 spaces and starts with '-'; its option column ends at the first
    run of two spaces (the help text). In that column the first token holds names (CLI11: `-h,--help`;
    argparse: `-h,`), and a later token is a name only after a token that ends with ',' (argparse's
    `-o OUT, --out OUT`, `--resume, --no-resume`): CLI11's `--target TEXT Excludes: --target-point` names
    --target only."""
    flags = set()
    for line in help_text.splitlines():
        if not re.match(r"^ {1,4}-", line):
            continue
        names_follow = True
        for token in re.split(r"\s{2,}", line.strip())[0].split():
            if names_follow and token.startswith("-"):
                flags.update(name for name in token.rstrip(",").split(",") if name.startswith("--"))
            names_follow = token.endswith(",")
    return flags - EXCLUDED


def help_groups(help_text: str) -> list[tuple[str, str]]:
    """[(title, text)] of a --help's option groups: a line at column 0 ending with ':' starts one (CLI11's
    "Options:", "Task:"; argparse's "options:", "evaluate's flags (...), passed to every shard unchanged:")."""
    groups = [("", [])]
    for line in help_text.splitlines():
        if re.match(r"^\S.*:$", line):
            groups.append((line[:-1], []))
        else:
            groups[-1][1].append(line)
    return [(title, "\n".join(lines)) for title, lines in groups]


def passed_on(title: str, commands) -> str | None:
    """The command whose flags a help group titled "OTHER's flags ..." passes on, else None."""
    found = re.match(r"^([\w-]+)'s flags\b", title)
    return found.group(1) if found and found.group(1) in commands else None


def _run_help(command: tuple[str, ...]) -> str:
    name, *sub = command
    if name in SCRIPTS:
        module, _, func = SCRIPTS[name].partition(":")
        argv = [sys.executable, "-c", f"import sys; from {module} import {func}; sys.argv[0] = {name!r}; {func}()"]
    else:
        argv = [str(guidewire_nav.app_path(name))]
    done = subprocess.run(argv + sub + ["--help"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, f"{' '.join(command)} --help exited {done.returncode}: {done.stderr[-2000:]}"
    return done.stdout


def _subcommands(help_text: str) -> list[str]:
    """argparse's sub-commands: the `{a,b}` choice the usage line ends with (`usage: gw-cluster [-h] {evaluate,bench} ...`)."""
    usage = help_text.split("\n\n", 1)[0]
    found = re.search(r"\{([\w,-]+)\} \.\.\.", usage)
    return found.group(1).split(",") if found else []


@pytest.fixture(scope="module")
def helps() -> dict[str, str]:
    """'command' or 'command sub' -> its --help text, for every C++ app and console script (run in parallel)."""
    missing = [str(guidewire_nav.app_path(a)) for a in APPS if not guidewire_nav.app_path(a).is_file()]
    if missing:
        pytest.skip(f"apps not built: {', '.join(missing)}; set GW_BUILD_DIR")
    commands = [(a,) for a in APPS] + [(s,) for s in SCRIPTS]
    with ThreadPoolExecutor(8) as pool:
        texts = dict(zip((" ".join(c) for c in commands), pool.map(_run_help, commands)))
    subs = [(name, sub) for name in SCRIPTS for sub in _subcommands(texts[name])]
    with ThreadPoolExecutor(8) as pool:
        texts.update(zip((" ".join(c) for c in subs), pool.map(_run_help, subs)))
    return texts


def doc_sections(markdown: str, commands) -> dict[str, str]:
    """Heading name -> its section's text: a command's name (the longest that starts the heading, backticks
    dropped) or TASK_OPTIONS_HEADING. A name given two sections fails."""
    headings = []  # (line index, level, key)
    lines = markdown.splitlines()
    in_fence = False
    for i, line in enumerate(lines):
        if line.startswith("```"):
            in_fence = not in_fence
        heading = None if in_fence else re.match(r"^(#+)\s+(.*)$", line)
        if heading:
            text = heading.group(2).replace("`", "").strip()
            key = max((c for c in [*commands, TASK_OPTIONS_HEADING] if re.match(re.escape(c) + r"(\s|$)", text)),
                      key=len, default=None)
            headings.append((i, len(heading.group(1)), key))
    sections = {}
    for n, (start, level, key) in enumerate(headings):
        if key is None:
            continue
        assert key not in sections, f"docs/commands.md: two sections for {key}"
        end = next((i for i, lvl, other in headings[n + 1:] if lvl <= level or other is not None), len(lines))
        sections[key] = "\n".join(lines[start + 1:end])
    return sections


def doc_flags(section: str, command: str, commands) -> set[str]:
    """The flags a section names for `command`: every --flag, less those in a code span or code-block line
    that starts with another command's name (or `python -m guidewire_nav....`)."""
    others = [c for c in commands if c != command and not command.startswith(c + " ")]

    def belongs_elsewhere(code: str) -> bool:
        code = code.strip()
        return (any(re.match(re.escape(c) + r"(\s|$)", code) for c in others)
                or re.match(r"(\S*python\S* )?-m guidewire_nav", code) is not None
                or code.startswith(".venv/bin/python"))

    kept = []
    in_fence = False
    for line in section.splitlines():
        if line.startswith("```"):
            in_fence = not in_fence
            continue
        if in_fence:
            if not belongs_elsewhere(line):
                kept.append(line)
            continue
        kept.append(re.sub(r"`([^`]*)`", lambda m: "" if belongs_elsewhere(m.group(1)) else m.group(0), line))
    return set(re.findall(r"(?<![\w-])--[a-z][a-z0-9-]*", "\n".join(kept))) - EXCLUDED


def test_option_flags_reads_cli11_and_argparse():
    cli11 = ("Options:\n  -h,--help                   Print this help\n"
             "  --target TEXT Excludes: --target-point\n                              target number, see --list\n"
             "  --json                      print JSON\n")
    assert option_flags(cli11) == {"--target", "--json"}
    argparse_help = ("options:\n  -h, --help            show this help\n  -o OUT, --out OUT     folder\n"
                     "  --resume, --no-resume\n                        continue, like --total-steps says\n"
                     "  --net-arch NET_ARCH   hidden layers\n")
    assert option_flags(argparse_help) == {"--out", "--resume", "--no-resume", "--net-arch"}


def test_doc_flags_follow_the_convention():
    doc = ("# Commands\n## navigate (the main job)\n```\nnavigate --anatomy F [--json]\n"
           "gw-cluster evaluate --rows X\n```\nLike `guidewire-server --step-cutoff S`, `--seed S` seeds.\n"
           "### navigate's output\n`--out DIR` writes\n## Task options\n`--task F`\n## gw-cluster\n"
           "### gw-cluster evaluate\n--rows\n")
    commands = ["navigate", "guidewire-server", "gw-cluster", "gw-cluster evaluate"]
    sections = doc_sections(doc, commands)
    assert set(sections) == {"navigate", TASK_OPTIONS_HEADING, "gw-cluster", "gw-cluster evaluate"}
    assert doc_flags(sections["gw-cluster"], "gw-cluster", commands) == set()
    assert doc_flags(sections["navigate"], "navigate", commands) == {"--anatomy", "--json", "--seed", "--out"}
    assert doc_flags(sections["gw-cluster evaluate"], "gw-cluster evaluate", commands) == {"--rows"}


def test_help_groups_find_passed_on_flags():
    text = ("options:\n  -h, --help  help\n  --out OUT   folder\n"
            "evaluate's flags (`evaluate --help`), passed to every shard unchanged:\n  --seed SEED  seed\n")
    groups = help_groups(text)
    assert [passed_on(title, ["evaluate"]) for title, _ in groups] == [None, None, "evaluate"]
    assert [option_flags(t) for _, t in groups] == [set(), {"--out"}, {"--seed"}]


def test_commands_md_documents_every_flag(helps):
    commands = sorted(helps)
    sections = doc_sections(DOC.read_text(), commands)
    problems = []
    for command in commands:
        if command not in sections:
            problems.append(f"{command}: no section in docs/commands.md (a heading starting with `{command}`)")
            continue
        documented = doc_flags(sections[command], command, commands)
        if command in TASK_OPTION_APPS:
            assert TASK_OPTIONS_HEADING in sections, f"docs/commands.md: no '{TASK_OPTIONS_HEADING}' section"
            documented |= doc_flags(sections[TASK_OPTIONS_HEADING], command, commands)
        listed, passed = set(), set()
        for title, text in help_groups(helps[command]):
            other = passed_on(title, commands)
            if other is None:
                listed |= option_flags(text)
            else:
                passed |= option_flags(text)
                for flag in sorted(option_flags(text) - option_flags(helps[other])):
                    problems.append(f"{command} {flag}: passed on as {other}'s, not in {other} --help")
        for flag in sorted(listed - documented):
            if (command, flag) not in ALLOWED:
                problems.append(f"{command} {flag}: in --help, not in docs/commands.md's section for it")
        for flag in sorted(documented - listed - passed):
            if (command, flag) not in ALLOWED:
                problems.append(f"{command} {flag}: in docs/commands.md's section for it, not in --help")
    assert not problems, "docs/commands.md and --help disagree:\n" + "\n".join(problems)


def test_every_documented_command_line_uses_existing_flags(helps):
    """A flag in a documented example or synopsis (docs_commands: the fenced blocks' and command tables'
    commands of README.md, docs/*.md and the folders' README.md files) that the command's --help does not list
    fails (a renamed or removed flag leaves no dead example behind). A sub-command that passes another command's
    flags on (gw-cluster evaluate) may use that command's too. A command marked as a record of an earlier
    commit (`<!-- docs-run: record: ... -->`) keeps that commit's flags and is not checked."""
    bad, seen = [], 0
    for doc in documented_commands():
        if doc.command is None or doc.marked("record"):
            continue
        command = doc.command if doc.command in helps else doc.command.split()[0]
        known = option_flags(helps[command]) | {"--help"}
        for title, _ in help_groups(helps[command]):
            if (other := passed_on(title, APPS)) is not None:
                known |= option_flags(helps[other])
        seen += 1
        bad += [f"{doc.where}: {doc.text[:80]}: {command} has no {flag}" for flag in doc.flags() if flag not in known]
    assert seen > 50, f"only {seen} documented command lines found: the scan is broken"
    assert not bad, "documented commands with flags their --help does not list:\n" + "\n".join(bad)
