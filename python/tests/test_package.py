"""The package's surface: the type stub lists exactly what the module
exports (functions, classes, their public methods), and every call has a
docstring."""

import ast
import os

import habuffer as hb

STUB = os.path.join(os.path.dirname(hb.__file__), "__init__.pyi")


def stub_names():
    tree = ast.parse(open(STUB).read())
    top, methods = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            methods[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        if isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
    return top, methods


def test_the_stub_lists_every_export_and_nothing_else():
    top, methods = stub_names()
    exported = set(hb.__all__) | {"__version__"}
    assert exported <= top | {"FRAGMENT_DTYPE"}, exported - top
    for cls in ("Buffer", "SpatialHash"):
        real = {n for n in dir(getattr(hb, cls)) if not n.startswith("__") or n == "__len__"}
        real.discard("__init__")
        assert real == methods[cls] - {"__init__"}, (cls, real ^ (methods[cls] - {"__init__"}))


def test_every_call_has_a_docstring():
    for name in hb.__all__:
        obj = getattr(hb, name)
        if callable(obj) and name not in ("DataError", "GlError", "SceneError"):
            assert (obj.__doc__ or "").strip(), name


def test_the_figures_run_on_the_gpu_path(gl_available):
    t = hb.figure_fig10(4, size=(32, 32), repeats=1)
    assert t.title == "fig10" and t.rows > 0 and (t["failures"] == 0).all()
    f = hb.figure_fig2("hairball", opacities=[0.5], size=(32, 32), repeats=1)
    assert f.rows > 0
