"""tools/ by topic (tools/_paths.py): every tool path the repository names exists, every tool is
in a listed topic folder under a name no other tool has (they share one import namespace), and
the tools import along the layers _paths.LAYERS declares (never bench).

doc/CHANGELOG.md (history) and results/ (records of past runs) keep the paths of their day."""
import ast
import os
import re
import sys

from conftest import root_dir

ROOT = root_dir()
TOOLS = os.path.join(ROOT, "tools")
sys.path.insert(0, TOOLS)
import _paths  # noqa: E402

# where the repository names tools: the docs, examples, workflow and the code that calls them
NAMING = ["README.md", "ellipsoid-dep", "CMakeLists.txt", "doc", "examples", "workflow", "bench",
          "tests", "tools", "src"]
HISTORY = [os.path.join("doc", "CHANGELOG.md")]
# tools/..., also after the repository's root ($ROOT/, {ROOT}/), not LAMMPS's tools/ folder
TOOL_PATH = re.compile(r"(?:(?<=ROOT/)|(?<=ROOT}/)|(?<![\w./-]))tools/[\w/]+\.(?:py|sh)\b")


def files(names):
    for name in names:
        path = os.path.join(ROOT, name)
        if os.path.isfile(path):
            yield path
        for folder, _, entries in os.walk(path):
            for entry in entries:
                yield os.path.join(folder, entry)


def named_tool_paths():
    """{path named: [file:line, ...]} over the files that name tools"""
    named = {}
    for path in files(NAMING):
        rel = os.path.relpath(path, ROOT)
        if rel in HISTORY:
            continue
        with open(path, "rb") as f:
            data = f.read()
        if b"\0" in data:
            continue
        for number, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
            for found in TOOL_PATH.findall(line):
                named.setdefault(found, []).append(f"{rel}:{number}")
    return named


def tool_modules():
    """{module name: [topic folder, ...]} of every .py below tools/ but LIGGGHTS's own"""
    modules = {}
    for path in files(["tools"]):
        rel = os.path.relpath(path, TOOLS)
        if rel.endswith(".py") and not rel.startswith("liggghts" + os.sep) and rel != "_paths.py":
            modules.setdefault(os.path.basename(rel)[:-3], []).append(os.path.dirname(rel))
    return modules


def imported_names(path):
    tree = ast.parse(open(path).read(), path)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            yield node.module.split(".")[0]


def test_every_named_tool_path_exists():
    named = named_tool_paths()
    assert "tools/liggghts/setup.sh" in named    # the search finds what it looks for
    missing = {p: where for p, where in named.items() if not os.path.isfile(os.path.join(ROOT, p))}
    assert not missing, "tool paths named but not in the repository:\n" + "\n".join(
        f"  {p}: {', '.join(where)}" for p, where in sorted(missing.items()))


def test_every_tool_is_in_one_listed_topic_folder():
    listed = set(_paths.LAYERS)
    assert all(os.path.isdir(folder) for folder in _paths.FOLDERS)
    for name, folders in tool_modules().items():
        assert len(folders) == 1, f"{name}.py in {folders}: one import namespace, one name"
        assert folders[0] in listed, f"tools/{folders[0]}/{name}.py: not in _paths.LAYERS"


def test_tools_import_along_the_layers():
    modules = {name: folders[0] for name, folders in tool_modules().items()}
    bench = {os.path.basename(p)[:-3] for p in files(["bench"]) if p.endswith(".py")} | {"bench"}
    wrong = []
    for name, topic in modules.items():
        allowed = {topic, *_paths.LAYERS[topic]}
        for imported in imported_names(os.path.join(TOOLS, topic, name + ".py")):
            if imported in bench or modules.get(imported, topic) not in allowed:
                wrong.append(f"tools/{topic}/{name}.py imports {imported}")
    assert not wrong, "\n".join(wrong)
