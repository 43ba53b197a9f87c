"""The layout docs/ARCHITECTURE.md describes, checked against the code: no import circles among
shaftfe's own modules (imports inside functions included, which hide them), and every file,
module and name the "Where things go" list points a maintainer to exists.

An arrow is an ``import`` statement naming a module of shaftfe. Not arrows: the package
``__init__`` files Python runs on the way to a submodule (a package's face; a package's own
imports are its arrows), and names imported from a string (``cli.COMMAND_MODULES``, the lazy
``__getattr__`` tables of ``shaftfe``, ``shaftfe.static`` and ``shaftfe.fatigue``), which no
reader of the source follows either."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "shaftfe"

# The circles left, each with its reason; anything else is a new circle and fails the test.
# None is left: the last one (model.loader ↔ model.derive) went when parsing moved to
# model.parse, which model.derive uses and model.loader.load_variant calls after it.
KNOWN_CIRCLES: set[frozenset[str]] = set()


def _modules() -> dict[str, Path]:
    out = {}
    for p in PKG.rglob("*.py"):
        parts = p.relative_to(ROOT).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        out[name] = p
    return out


def _type_checking_lines(tree: ast.AST) -> set[int]:
    """The lines of ``if TYPE_CHECKING:`` blocks (annotations only: no import at run time)."""
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test) in ("TYPE_CHECKING",
                                                                    "typing.TYPE_CHECKING"):
            for sub in node.body:
                lines.update(range(sub.lineno, (sub.end_lineno or sub.lineno) + 1))
    return lines


def import_graph() -> dict[str, set[str]]:
    """{module: the shaftfe modules it imports anywhere in it}, run-time imports only."""
    mods = _modules()
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for name, path in mods.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skip = _type_checking_lines(tree)
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(tree):
            if getattr(node, "lineno", None) in skip:
                continue
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")
                    up = up[:len(up) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in mods else base
                           for a in node.names]
            for t in targets:
                while t and t not in mods:
                    t = t.rpartition(".")[0]
                if t and t != name:
                    graph[name].add(t)
    return graph


def circles(graph: dict[str, set[str]]) -> set[frozenset[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: set[frozenset[str]] = set()

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.add(frozenset(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_graph_reader_finds_a_circle():
    """The reader and Tarjan's search on a made-up graph: a 3-circle, a 2-circle, a chain."""
    g = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": {"e"}, "e": {"d"}, "f": {"a"}}
    assert circles(g) == {frozenset("abc"), frozenset("de")}
    real = import_graph()
    assert "shaftfe.fe.facets" in real["shaftfe.fe.assembly"]           # a top-level import
    assert "shaftfe.static.cache" in real["shaftfe.static.solve"]
    # one inside a function
    assert "shaftfe.beam.solve" in real["shaftfe.machine_elements.bearings"]


def test_no_import_circles_but_the_known_ones():
    """No module of shaftfe reaches itself through imports, counting those inside functions
    (which hide a circle from Python, not from a reader), except ``KNOWN_CIRCLES``."""
    found = circles(import_graph())
    assert found - KNOWN_CIRCLES == set(), sorted(sorted(c) for c in found - KNOWN_CIRCLES)
    assert KNOWN_CIRCLES - found == set(), "a known circle is gone: take it off the list"


def _tables():
    """docs/tables.py, the generator of ARCHITECTURE.md's module index (not a package)."""
    spec = importlib.util.spec_from_file_location("docs_tables", ROOT / "docs" / "tables.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# The pipeline's order, lowest first (docs/tables.py: the floors of docs/ARCHITECTURE.md's
# module index): a module imports only modules of its own package or of packages before its
# own, except the arrows "Rules the layout keeps" names with their reasons (``UPWARD_ARROWS``).
PIPELINE = _tables().PIPELINE
UPWARD_ARROWS = {
    ("shaftfe.model.parse", "shaftfe.solid.plan"),     # a file is refused when it is read
    ("shaftfe.solid.mesh", "shaftfe.fe.assembly"),     # every P2 mesh inverts curved tets
}


def _package(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else parts[0]


def test_imports_run_down_the_pipeline():
    """Every import (those inside functions too) runs down ``PIPELINE`` or stays in its own
    package, but the ``UPWARD_ARROWS`` ARCHITECTURE.md names; a new package must take its
    place in the pipeline first."""
    graph = import_graph()
    rank = {p: i for i, p in enumerate(PIPELINE)}
    assert {_package(m) for m in graph} <= set(rank), "a package not placed in PIPELINE"
    up = {(a, b) for a, bs in graph.items() for b in bs
          if rank[_package(b)] > rank[_package(a)]}
    assert up == UPWARD_ARROWS, sorted(up ^ UPWARD_ARROWS)
    text = (ROOT / "docs" / "ARCHITECTURE.md").read_text(encoding="utf-8")
    rules = text.split("## Rules the layout keeps", 1)[1].split("\n## ", 1)[0]
    exceptions = rules.split("deliberate exceptions", 1)[1].split("\n- ", 1)[0]
    for a, b in UPWARD_ARROWS:                  # both ends named there, with the reason
        for m in (a, b):
            assert f"`{m.removeprefix('shaftfe.')}" in exceptions, m


def _where_things_go() -> list[str]:
    """The backticked names of the section, a name broken over two lines joined again."""
    text = (ROOT / "docs" / "ARCHITECTURE.md").read_text(encoding="utf-8")
    section = text.split("## Where things go", 1)[1].split("\n## ", 1)[0]
    return [re.sub(r"\s*\n\s*", "", n) for n in re.findall(r"`([^`]+)`", section)]


def _defined_names() -> set[str]:
    """Every function, class and assigned name of the package, at any depth."""
    out: set[str] = set()
    for path in _modules().values():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                out.add(node.name)
            elif isinstance(node, (ast.Assign, ast.AnnAssign)):
                for t in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                    out.update(n.id for n in ast.walk(t) if isinstance(n, ast.Name))
    return out


def _resolve(dotted: list[str]) -> bool:
    """Does ``shaftfe.<dotted>`` name a module, or an attribute chain of the longest module (a
    name the module imports counts: it is reached there)?"""
    for k in range(len(dotted), 0, -1):
        try:
            obj = importlib.import_module("shaftfe." + ".".join(dotted[:k]))
        except ModuleNotFoundError:
            continue
        for attr in dotted[k:]:
            if not hasattr(obj, attr):
                return False
            obj = getattr(obj, attr)
        return True
    return False


# a backticked text that is no place: a value, a call, a pattern, a command line
NOT_A_PLACE = re.compile(r"[<>=(\[ ]|^-|:")


def test_where_things_go_names_what_exists():
    """Every backticked name of the "Where things go" list of docs/ARCHITECTURE.md: a file or
    folder (``solid/plan.py``, ``fatigue/methods/``, ``reports/benchmarks/kt_undercuts.json``)
    exists; a module path (``beam/model._shoulders``, ``fatigue.methods.METHODS``) resolves;
    a bare name (``kind_of``, ``MeshLevel``) is defined in the package. Nothing else is passed
    over but texts that are no place (``NOT_A_PLACE``: values, calls, patterns)."""
    defined = _defined_names()
    places = 0
    for n in _where_things_go():
        if NOT_A_PLACE.search(n):
            continue
        head, _, rest = n.rpartition("/")
        if n.endswith("/") or re.search(r"\.(py|json|toml|md)$", n):
            assert (PKG / n).exists() or (ROOT / n).exists(), n
        elif head:                             # dir/module.name: the module's attribute
            mod, *attrs = rest.split(".")
            assert _resolve([*head.split("/"), mod, *attrs]), n
        elif "." in n:
            assert _resolve(n.split(".")), n
        else:
            assert re.fullmatch(r"[A-Za-z_][A-Za-z_0-9]*", n) and n in defined, n
        places += 1
    assert places > 0               # the section was found and read


def test_the_module_index_is_every_module_floor_by_floor():
    """docs/ARCHITECTURE.md's "Every module, floor by floor" is what docs/tables.py makes of the
    package now: every module under its floor of ``PIPELINE``, with its docstring's first
    sentence (a module added, moved or described anew fails here until ``make tables``)."""
    tables = _tables()
    text = (ROOT / "docs" / "ARCHITECTURE.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- table:modules -->\n(.*?)<!-- /table -->", text, re.S)
    assert block is not None, "the module index's markers are missing"
    assert block.group(1).strip() == tables.modules().strip(), \
        "run python docs/tables.py modules"
    listed = set(re.findall(r"^- `([^`]+)`:", block.group(1), re.M))
    assert listed == {m.removeprefix("shaftfe.") if m != "shaftfe" else m
                      for m in _modules() if m == "shaftfe" or not (
                          PKG / m.removeprefix("shaftfe.").replace(".", "/")).is_dir()}
