"""The shell commands the docs give, read once for two tests: test_docs_flags (every flag a documented command
uses exists) and test_docs_run (every documented command runs).

Read: README.md, docs/*.md and the folders' README.md files (one and two levels down). A command is a
command line of a fenced block (no language, or bash/sh/shell/console), or the first cell of a command table's
row when that cell is one code span (a table whose header's first cell is "command", as README's
"| `evaluate --out results` | ... |"), that runs one of the project's commands:
- a C++ app of apps/CMakeLists.txt: `build/apps/NAME`, or NAME bare;
- a console script of training/pyproject.toml: `.venv/bin/NAME`, or NAME bare (with its argparse sub-command,
  `gw-cluster evaluate`), and `python -m guidewire_nav.MODULE` (`.venv/bin/python`, `python3`), named after
  the console script that runs MODULE's main where there is one;
- a project script: `python3 results/.../X.py`, `python3 scripts/X.py`, `bash scripts/X.sh`, and `cmake`.
Backslash continuations are joined (the command's line is its first), a `#` comment is dropped, and a line
holding several commands (`&&`, `||`, `;`, a pipe outside synopsis brackets) gives each its own.

A command's markers are the `<!-- docs-run: KIND: VALUE -->` (or `KIND "TEXT": VALUE`, for its block's
commands that contain TEXT) lines right above its fenced block, or above its table; test_docs_run says what
each kind does. One concerns both tests: `record: WHEN` marks a command as it ran at an earlier commit, with
that commit's flags (its doc gives today's spelling beside it): not run, and its flags not checked.
"""
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SCRIPTS = tomllib.loads((REPO / "training" / "pyproject.toml").read_text())["project"]["scripts"]
APPS = re.findall(r"^gw_add_app\(([\w-]+)", (REPO / "apps" / "CMakeLists.txt").read_text(), re.M)
MODULE_SCRIPTS = {entry.partition(":")[0]: name for name, entry in SCRIPTS.items() if entry.endswith(":main")}
SHELL_FENCES = {"", "bash", "sh", "shell", "console"}
MARKER = re.compile(r'^\s*<!--\s*docs-run:\s*([\w-]+)(?:\s+"([^"]*)")?:\s*(.*?)\s*-->\s*$')
REDIRECT = re.compile(r"^(\d?>>?|<)")


def doc_files() -> list[Path]:
    return [REPO / "README.md", *sorted((REPO / "docs").glob("*.md")), *sorted(REPO.glob("*/README.md")),
            *sorted(REPO.glob("*/*/README.md"))]


@dataclass(frozen=True)
class DocCommand:
    path: Path              # the doc, relative to REPO
    line: int               # the command's first line in it (1-based)
    text: str               # the command as the doc writes it (continuations joined, comment dropped)
    name: str               # 'navigate', 'gw-train', 'python3 results/x/summarize.py', 'bash scripts/test.sh'
    command: str | None     # the command whose --help lists its flags ('gw-cluster evaluate'); None: a script
    prefix: int             # how many of its words name the program ('.venv/bin/python -m guidewire_nav.train': 3)
    unit: str               # 'FILE:LINE' of its block (or table row): a unit's commands run in order
    markers: tuple          # ((kind, TEXT or None, value), ...): the docs-run comments above its block or table

    @property
    def where(self) -> str:
        return f"{self.path}:{self.line}"

    def marked(self, kind: str) -> list[str]:
        """The values of its markers of this kind that apply to it: those without TEXT, and those whose TEXT
        is in its command."""
        return [value for k, text, value in self.markers if k == kind and (text is None or text in self.text)]

    def flags(self) -> list[str]:
        """The long flags it uses, synopsis brackets and alternatives (`[--x`, `|--y`) included, up to a
        redirection."""
        flags = []
        for token in self.text.split()[self.prefix:]:
            if REDIRECT.match(token):
                break
            flags += re.findall(r"(?:^|[\[|(])(--[a-z][\w-]*)", token)
        return flags


def split_commands(line: str) -> list[str]:
    """A shell line's commands: split at `&&`, `||`, `;` and `|` outside quotes and brackets (a synopsis's
    `[--target N | --target-point P]` is one command, and so is a pattern's `<a|b>`), after dropping a `#`
    comment."""
    parts, start, depth, quote, i = [], 0, 0, None, 0
    while i < len(line):
        c = line[i]
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or line[i - 1].isspace()):
            break
        elif c in "[({":
            depth += 1
        elif c in "])}":
            depth = max(0, depth - 1)
        elif depth == 0 and (line.startswith(("&&", "||"), i) or c == ";" or c == "|" and not _alternatives(line, i)):
            parts.append(line[start:i])
            i += 2 if line.startswith(("&&", "||"), i) else 1
            start = i
            continue
        i += 1
    parts.append(line[start:i])
    return [p.strip() for p in parts if p.strip()]


def _alternatives(line: str, i: int) -> bool:
    """Whether the `|` at line[i] separates a pattern's alternatives (`NAME_<alone|assist>.json`), no pipe."""
    return bool(re.search(r"<[\w./-]*$", line[:i]) and re.match(r"[\w|./-]*>", line[i + 1:]))


def program(tokens: list[str]) -> tuple[str, str | None, int] | None:
    """(name, the command whose --help lists its flags, how many tokens name it) of the project command a
    command's tokens run, else None. A sub-command (`gw-cluster evaluate`) is not counted in the tokens."""
    if not tokens:
        return None
    first, used = re.sub(r"^(?:\S*/)?(?:build/apps|\.venv/bin)/", "", tokens[0]), 1
    if re.fullmatch(r"(?:\S*/)?python3?", first) and len(tokens) > 1:
        if tokens[1] == "-m" and len(tokens) > 2 and tokens[2].startswith("guidewire_nav"):
            first, used = MODULE_SCRIPTS.get(tokens[2], f"python -m {tokens[2]}"), 3
        elif re.fullmatch(r"(scripts|results)/\S+\.py", tokens[1]):
            return f"python3 {tokens[1]}", None, 2
        else:
            return None
    if first == "bash" and len(tokens) > 1 and re.fullmatch(r"(scripts|results)/\S+\.sh", tokens[1]):
        return f"bash {tokens[1]}", None, 2
    if first == "cmake":
        return "cmake", None, 1
    if first in APPS:
        return first, first, used
    if first in SCRIPTS:
        sub = tokens[used] if len(tokens) > used else ""
        return first, f"{first} {sub}" if re.fullmatch(r"[a-z]+", sub) else first, used
    if first.startswith("python -m "):
        return first, None, used
    return None


def _logical_lines(lines: list[str], first: int):
    """(line number, text) of a block's lines with backslash continuations joined."""
    held, at = "", None
    for n, text in enumerate(lines, first):
        if at is None:
            at = n
        if text.rstrip().endswith("\\"):
            held += text.rstrip()[:-1] + " "
            continue
        yield at, held + text
        held, at = "", None
    if at is not None:
        yield at, held


def _markers(lines: list[str], above: int) -> tuple:
    """The docs-run comments on the lines right above index `above` (0-based)."""
    found = []
    i = above - 1
    while i >= 0 and (m := MARKER.match(lines[i])):
        found.insert(0, m.groups())
        i -= 1
    return tuple(found)


def _commands(path, unit, markers, numbered_lines):
    for n, text in numbered_lines:
        for part in split_commands(text):
            found = program(part.split())
            if found:
                yield DocCommand(path, n, part, *found, unit, markers)


def _fenced(path: Path, lines: list[str]):
    i = 0
    while i < len(lines):
        opening = re.match(r"^\s*```([\w+-]*)\s*$", lines[i])
        if not opening:
            i += 1
            continue
        end = next((j for j in range(i + 1, len(lines)) if re.match(r"^\s*```\s*$", lines[j])), len(lines))
        if opening.group(1) in SHELL_FENCES:
            yield from _commands(path, f"{path}:{i + 1}", _markers(lines, i),
                                 _logical_lines(lines[i + 1:end], i + 2))
        i = end + 1


def _tables(path: Path, lines: list[str]):
    """The commands of command tables: tables whose header's first cell is `command`, one command a row
    whose first cell is one code span."""
    in_fence, table_start = False, None
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
        if in_fence or not line.startswith("|"):
            table_start = None
            continue
        table_start = i if table_start is None else table_start
        cell = re.match(r"^\|\s*`([^`]+)`\s*\|", line)
        if cell and re.match(r"^\|\s*command\s*\|", lines[table_start]):
            yield from _commands(path, f"{path}:{i + 1}", _markers(lines, table_start), [(i + 1, cell.group(1))])


def commands_in(path: Path, text: str) -> list[DocCommand]:
    """The commands of one doc (path: as the commands name it), in line order."""
    lines = text.splitlines()
    return sorted([*_fenced(path, lines), *_tables(path, lines)], key=lambda c: c.line)


def documented_commands() -> list[DocCommand]:
    """Every documented command, file by file (doc_files' order), in line order."""
    return [c for path in doc_files() for c in commands_in(path.relative_to(REPO), path.read_text())]
