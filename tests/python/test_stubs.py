"""The type stub contact2d/_contact2d.pyi is the extension: every public
class, attribute and method of _contact2d is in it, of the same kind, with
the same parameter names, and it names nothing the extension lacks. It
ships in the package with py.typed (PEP 561), beside the extension."""

import ast
import re
from pathlib import Path

import contact2d
from contact2d import _contact2d

STUB = Path(contact2d.__file__).with_name("_contact2d.pyi")
# Scene.load sets `source` on the scene it returns (py::dynamic_attr): no
# class attribute, but an editor should know it.
DYNAMIC = {("Scene", "source")}


def dunder(name):
    return name.startswith("__") and name.endswith("__")


def stub_tree():
    return ast.parse(STUB.read_text(encoding="utf-8"))


def stub_members(body):
    """{name: kind} of a stub's class or module body, and {name: params}."""
    kinds, params = {}, {}
    for node in body:
        if isinstance(node, ast.AnnAssign):
            kinds[node.target.id] = "attribute"
        elif isinstance(node, ast.FunctionDef):
            decorators = {d.id for d in node.decorator_list if isinstance(d, ast.Name)}
            kinds[node.name] = ("readonly" if "property" in decorators else
                                "static" if "staticmethod" in decorators else "method")
            params[node.name] = [a.arg for a in node.args.args if a.arg != "self"]
        elif isinstance(node, ast.ClassDef):
            kinds[node.name] = "class"
    return kinds, params


def runtime_kind(value):
    if isinstance(value, property):
        return "attribute" if value.fset is not None else "readonly"
    if isinstance(value, staticmethod):
        return "static"
    if isinstance(value, type):
        return "class"
    if callable(value):
        return "method"
    return "attribute"


def pybind_params(function):
    """The parameter names of pybind11's signature line: "f(arg0: float, ...)"."""
    first = (function.__doc__ or "").splitlines()[0] if function.__doc__ else ""
    inside = first[first.index("(") + 1:first.rindex(")")] if "(" in first else ""
    names = re.findall(r"(?:^|, )(\w+):", inside)
    return [n for n in names if n != "self"]


def test_the_stub_and_py_typed_are_in_the_package():
    assert STUB.is_file(), STUB
    assert STUB.with_name("py.typed").is_file()


def test_the_module_names_are_the_extensions():
    kinds, params = stub_members(stub_tree().body)
    runtime = {name: runtime_kind(value) for name, value in vars(_contact2d).items()
               if not dunder(name)}
    runtime["__version__"] = "attribute"
    assert kinds == runtime
    for name, value in vars(_contact2d).items():
        if runtime.get(name) == "method":  # _simulate(...): pybind11 names them arg0, arg1, ...
            assert len(params[name]) == len(pybind_params(value)), name


def test_every_class_member_is_in_the_stub_and_nothing_else():
    classes = {node.name: node for node in stub_tree().body if isinstance(node, ast.ClassDef)}
    for class_name, node in classes.items():
        cls = getattr(_contact2d, class_name)
        kinds, params = stub_members(node.body)
        runtime = {name: runtime_kind(value) for name, value in vars(cls).items()
                   if not name.startswith("_")}
        for owner, name in DYNAMIC:
            if owner == class_name:
                assert name not in runtime and kinds.pop(name) == "attribute"
        assert kinds.pop("__init__", None) is None or "__init__" in vars(cls)
        assert kinds == runtime, class_name
        if "__init__" in params:
            assert params["__init__"] == pybind_params(cls.__init__), class_name
    loaded = contact2d.Scene.load("validation/scenes/box.toml")
    assert loaded.source == "validation/scenes/box.toml"  # the DYNAMIC attribute exists


def test_a_missing_or_extra_member_fails():
    """The comparison above can fail: a stub without Contact.k, or with a
    made-up attribute, differs from the extension."""
    node = next(n for n in stub_tree().body if isinstance(n, ast.ClassDef) and n.name == "Contact")
    kinds, _ = stub_members(node.body)
    runtime = {name: runtime_kind(value) for name, value in vars(contact2d.Contact).items()
               if not name.startswith("_")}
    assert kinds == runtime
    assert {k: v for k, v in kinds.items() if k != "k"} != runtime
    assert {**kinds, "stiffness": "attribute"} != runtime
