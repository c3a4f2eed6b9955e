"""The core's layout: each layer folder includes only the layers below it, and no core function is long.

Reads the sources as text (no build needed): an upward or sideways include fails here."""
import pathlib
import re

CORE = pathlib.Path(__file__).resolve().parents[1] / "plugin" / "core"
# Bottom to top; layers of one rank are siblings that never include each other.
RANK = dict(mesh=0, solid=1, hull=2, prepare=3, recursion=4, decompose3=5, polygon=5, structure=6, io=7, api=8)
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]acd/(\w+)/[\w.]+[>"]', re.M)


def layer_files():
    for f in sorted((CORE / "acd").rglob("*")):
        if f.suffix in (".h", ".cpp"):
            yield f.parent.name, f


def test_every_layer_folder_is_ranked_and_documented():
    folders = {d.name for d in (CORE / "acd").iterdir() if d.is_dir()}
    assert folders == set(RANK), f"layer folders {sorted(folders)} against the ranks {sorted(RANK)}"
    for name in folders:
        assert (CORE / "acd" / name / "README.md").is_file(), f"acd/{name} has no README.md"


def test_includes_point_down():
    bad = []
    for layer, f in layer_files():
        for used in INCLUDE.findall(f.read_text()):
            assert used in RANK, f"{f.relative_to(CORE)} includes an unknown layer acd/{used}"
            if used != layer and RANK[used] >= RANK[layer]:
                bad.append(f"{f.relative_to(CORE)} includes acd/{used}/ (rank {RANK[used]} >= {RANK[layer]})")
    assert not bad, "\n".join(bad)


def test_the_check_sees_an_upward_include(tmp_path):
    """The pattern above matches the include forms the core uses."""
    assert INCLUDE.findall('#include "acd/io/tree_io.h"\n#include <acd/mesh/mesh.h>\n') == ["io", "mesh"]


def function_lengths(text):
    """(name, lines) of each function body at namespace level or in a class: a line ending in ')' or
    'const' (or a signature line) followed by a line '{' at the same indentation, up to its '}'."""
    lines = text.split("\n")
    out = []
    for i, line in enumerate(lines[1:], 1):
        m = re.match(r"^(\t*)\{\s*$", line)
        if not m:
            continue
        sig = lines[i - 1]
        if not re.search(r"\)\s*(const)?\s*(override)?\s*$", sig) or re.match(r"^\s*(if|for|while|switch)\b", sig):
            continue
        indent = m.group(1)
        for j in range(i + 1, len(lines)):
            if lines[j] == indent + "}" or lines[j].startswith(indent + "};"):
                name = re.findall(r"([\w:~]+)\s*\(", sig)
                out.append((name[0] if name else sig.strip(), j - i - 1))
                break
    return out


def test_no_core_function_over_60_lines():
    long = [f"{f.relative_to(CORE)}: {name} {n} lines" for _, f in layer_files()
            for name, n in function_lengths(f.read_text()) if n > 60]
    assert not long, "\n".join(long)


def test_the_length_check_counts_a_body():
    body = "int f(int a)\n{\n" + "\ta += 1;\n" * 61 + "\treturn a;\n}\n"
    assert function_lengths(body) == [("f", 62)]
