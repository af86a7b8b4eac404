"""The type stub of the compiled module says exactly what the module has: the same names,
and for every function and method the same parameters (names, kinds and defaults)."""

import ast
import inspect
import pathlib

import pytest

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
    for cls, stub in members.items():
        have = {n for n in vars(getattr(compiled, cls)) if not n.startswith("_")}
        assert stub - {"__init__"} == have, cls


def test_the_package_is_typed():
    assert STUB.with_name("py.typed").exists()


# --- Signatures ------------------------------------------------------------------------

NO_DEFAULT = "(none)"


def _decorators(node: ast.FunctionDef) -> set:
    return {d.id for d in node.decorator_list if isinstance(d, ast.Name)}


def stub_parameters(node: ast.FunctionDef) -> list:
    """(name, kind, default) of each parameter of a stubbed function, `self` left out;
    a default is the repr of its literal value."""
    a = node.args
    positional = a.posonlyargs + a.args
    defaults = [NO_DEFAULT] * (len(positional) - len(a.defaults)) + [
        repr(ast.literal_eval(d)) for d in a.defaults
    ]
    out = [
        (p.arg, "positional-only" if i < len(a.posonlyargs) else "positional or keyword", d)
        for i, (p, d) in enumerate(zip(positional, defaults))
    ]
    if a.vararg:
        out.append((a.vararg.arg, "variadic positional", NO_DEFAULT))
    for p, d in zip(a.kwonlyargs, a.kw_defaults):
        out.append((p.arg, "keyword-only", NO_DEFAULT if d is None else repr(ast.literal_eval(d))))
    if a.kwarg:
        out.append((a.kwarg.arg, "variadic keyword", NO_DEFAULT))
    if "staticmethod" not in _decorators(node) and out and out[0][0] == "self":
        out = out[1:]
    return out


def runtime_parameters(obj, method: bool) -> list:
    """The same from the compiled object's own signature (its `__text_signature__`)."""
    params = list(inspect.signature(obj).parameters.values())
    if method:
        assert params and params[0].name == "self", params
        params = params[1:]
    return [
        (
            p.name,
            p.kind.description,
            NO_DEFAULT if p.default is inspect.Parameter.empty else repr(p.default),
        )
        for p in params
    ]


def stubbed_callables():
    """(label, stub node, compiled object, is a method) for every function, method and
    constructor the stub declares; properties are (label, node, descriptor, None)."""
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            yield node.name, node, getattr(compiled, node.name), False
        if isinstance(node, ast.ClassDef):
            cls = getattr(compiled, node.name)
            for member in node.body:
                if not isinstance(member, ast.FunctionDef):
                    continue
                label = f"{node.name}.{member.name}"
                if member.name == "__init__":
                    yield label, member, cls, False
                elif "property" in _decorators(member):
                    yield label, member, inspect.getattr_static(cls, member.name), None
                else:
                    yield label, member, getattr(cls, member.name), (
                        "staticmethod" not in _decorators(member)
                    )


CALLABLES = list(stubbed_callables())


@pytest.mark.parametrize("label,node,obj,method", CALLABLES, ids=[c[0] for c in CALLABLES])
def test_each_stubbed_signature_is_the_compiled_one(label, node, obj, method):
    if method is None:
        assert inspect.isgetsetdescriptor(obj) or isinstance(obj, property), (
            f"{label} is stubbed as a property but is {type(obj).__name__}"
        )
        return
    static = "staticmethod" in _decorators(node)
    if static:
        cls_name, name = label.split(".")
        assert isinstance(inspect.getattr_static(getattr(compiled, cls_name), name), staticmethod), (
            f"{label} is stubbed as a static method but is not one"
        )
    elif "." in label and node.name != "__init__":
        cls_name, name = label.split(".")
        assert not isinstance(
            inspect.getattr_static(getattr(compiled, cls_name), name), (staticmethod, classmethod)
        ), f"{label} is stubbed as a method of instances but is not one"
    assert runtime_parameters(obj, method) == stub_parameters(node), label


def test_a_class_without_a_stubbed_constructor_has_none():
    # World and TestCostTree are made by their static methods: a class whose stub has no
    # __init__ must not have a constructor the stub does not show.
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    for node in tree.body:
        if not isinstance(node, ast.ClassDef):
            continue
        cls = getattr(compiled, node.name)
        if issubclass(cls, BaseException):
            continue
        if not any(isinstance(m, ast.FunctionDef) and m.name == "__init__" for m in node.body):
            assert getattr(cls, "__text_signature__", None) is None, node.name
            with pytest.raises(TypeError):
                cls()


def _parse_def(source: str) -> ast.FunctionDef:
    node = ast.parse(source).body[0]
    assert isinstance(node, ast.FunctionDef)
    return node


def test_the_comparison_sees_a_wrong_default_a_wrong_name_and_a_missing_parameter():
    # The check itself, on the compiled Classifier(kind, costs, tolerance=1).
    right = _parse_def("def __init__(self, kind: str, costs: list, tolerance: int = 1) -> None: ...")
    assert runtime_parameters(compiled.Classifier, False) == stub_parameters(right)
    for wrong in (
        "def __init__(self, kind: str, costs: list, tolerance: int = 2) -> None: ...",
        "def __init__(self, kind: str, costs: list, tolerance: float = 1.0) -> None: ...",
        "def __init__(self, kind: str, prices: list, tolerance: int = 1) -> None: ...",
        "def __init__(self, kind: str, costs: list) -> None: ...",
        "def __init__(self, kind: str, costs: list, *, tolerance: int = 1) -> None: ...",
        "def __init__(self, kind: str, costs: list, tolerance: int) -> None: ...",
    ):
        assert runtime_parameters(compiled.Classifier, False) != stub_parameters(
            _parse_def(wrong)
        ), wrong
