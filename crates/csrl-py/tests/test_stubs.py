"""The type stub of the compiled module names exactly what the module has."""

import ast
import pathlib

import csrl
import csrl._csrl as compiled

STUB = pathlib.Path(csrl.__file__).with_name("_csrl.pyi")


def stubbed():
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    names, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        if isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return names, members


def test_every_public_name_has_a_stub_and_no_stub_is_stale():
    names, members = stubbed()
    public = {n for n in dir(compiled) if not n.startswith("_")} | {"__version__"}
    assert names == public
    for cls in ("World", "Classifier", "TestCostTree"):
        have = {n for n in dir(getattr(compiled, cls)) if not n.startswith("_")}
        assert members[cls] - {"__init__"} == have, cls


def test_the_package_is_typed():
    assert STUB.with_name("py.typed").exists()
