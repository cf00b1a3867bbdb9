"""Short functions (docs/architecture.md, "Style"): no C++ or Python function outside a `main` is longer than
80 lines, and each `main` is shorter than 60; a long routine is a list of named stages, each its own function.

Lengths count from the line that opens the body's brace (C++; the signature's last line) or the `def` line
(Python) to the closing line. The C++ reader strips comments and string literals, then tracks braces: a brace
whose head has a `)` (a signature; a lambda inside a function is part of it) at namespace or class level opens a
function.
Tests (Catch2 TEST_CASEs, pytest functions) are not counted: a test reads best as one scenario."""
import ast
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
CPP_TOPS = ("base", "engine", "task", "plan", "centerline", "anatomy_gen", "policy", "lib", "apps")
PY_TOPS = ("training", "scripts", "results", "anatomies")
MAX_LINES, MAX_MAIN_LINES = 80, 59
SCOPE = re.compile(r"\b(namespace|struct|class|union|extern)\b")  # braces that hold functions
DATA = re.compile(r"\benum\b|=\s*$")  # braces that hold data


def cpp_functions(text):
    """[(name, first line, line count)] of the functions defined at namespace level in a C++ source."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    text = re.sub(r'"(\\.|[^"\\\n])*"', '""', text)
    text = re.sub(r"'(\\.|[^'\\\n])'", "''", text)
    text = re.sub(r"^[ \t]*#[^\n]*", "", text, flags=re.M)
    found, stack, head, line, opened = [], [], "", 1, None
    for ch in text:
        if ch == "{":
            last = re.split(r"[;{}]", head)[-1]
            if "fn" in stack or "block" in stack:
                stack.append("block")
            elif SCOPE.search(last):
                stack.append("scope")
            elif ")" in last and not DATA.search(last):
                stack.append("fn")
                opened = (line, " ".join(last.split())[-100:])
            else:
                stack.append("block")
            head = ""
        elif ch == "}":
            kind = stack.pop() if stack else None
            if kind == "fn":
                found.append((opened[1], opened[0], line - opened[0] + 1))
            head = ""
        else:
            head += ch
            if ch == "\n":
                line += 1
    return found


def too_long(name, count):
    is_main = re.search(r"(^|\W)main\s*\(", name) or name == "main"
    return count > (MAX_MAIN_LINES if is_main else MAX_LINES)


def test_cpp_functions_are_short():
    long = []
    for top in CPP_TOPS:
        for path in sorted((REPO / top).rglob("*.[ch]pp")):
            for name, first, count in cpp_functions(path.read_text(errors="replace")):
                if too_long(name, count):
                    long.append(f"{path.relative_to(REPO)}:{first}: {count} lines: {name}")
    assert not long, "functions over the limit (80 lines, a main 59):\n" + "\n".join(long)


def test_python_functions_are_short():
    long = []
    for top in PY_TOPS:
        for path in sorted((REPO / top).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    count = node.end_lineno - node.lineno + 1
                    if too_long(node.name, count):
                        long.append(f"{path.relative_to(REPO)}:{node.lineno}: {count} lines: {node.name}")
    assert not long, "functions over the limit (80 lines, a main 59):\n" + "\n".join(long)


def test_the_reader_finds_a_long_function():
    # The reader itself: a 90-line function is found and counted, a struct and a namespace are not functions.
    body = "\n".join(f"  x += {i};" for i in range(88))
    text = (f'#include <a>\nnamespace a {{\nstruct S {{ int f() {{ return 1; }} }};\nint g(int x)\n{{\n{body}\n}}\n'
            f'enum class E {{ A, B }};\nconst int t[] = {{1, 2}};\n}}\n')
    found = [(n.strip(), first, count) for n, first, count in cpp_functions(text)]
    assert found == [("int f()", 3, 1), ("int g(int x)", 5, 90)]
    assert too_long("int g(int x)", 90) and not too_long("int g(int x)", 80)
    assert too_long("int main(int argc, char** argv)", 60) and not too_long("int main()", 59)
