"""The type stubs and the signatures follow the engine's registry: every parameter of every
command a function runs is a keyword of the function, in its signature, its docstring and
the shipped ``__init__.pyi`` (regenerated here: the file cannot go stale)."""

import ast
import inspect
from pathlib import Path

import tensegrity as tg
from tensegrity import _stubgen

STUBS = Path(tg.__file__).with_name("__init__.pyi")
SOURCE_STUBS = Path(__file__).resolve().parents[1] / "python" / "tensegrity" / "__init__.pyi"

#: function → the registry commands whose parameters it takes
FUNCTIONS = {
    "statics": ["statics"], "simulate": ["simulate"], "toroid": ["toroid"], "roll": ["roll"],
    "tipover": ["tipover", "tipover_dynamic", "tipover_rolling"], "michell": ["michell"],
    "michell_optimize": ["michell_optimize"], "michell_table": ["michell_table"],
    "tbar": ["tbar"], "tbar_roll": ["tbar_roll"], "design": ["design"],
}
if "formfind" in tg.commands():
    FUNCTIONS["formfind"] = ["formfind"]


def test_the_shipped_stubs_are_the_generated_ones():
    text = _stubgen.stubs()
    assert SOURCE_STUBS.read_text() == text, "run: python -m tensegrity._stubgen > " + str(SOURCE_STUBS)
    if STUBS.exists():
        assert STUBS.read_text() == text


def test_stubs_list_every_registry_parameter_with_a_docstring():
    tree = ast.parse(SOURCE_STUBS.read_text())
    defs = {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}
    registry = tg.commands()
    for name, commands in FUNCTIONS.items():
        f = defs[name]
        args = {a.arg for a in f.args.args + f.args.kwonlyargs}
        doc = ast.get_docstring(f)
        assert doc and "Parameters" in doc, name
        for c in commands:
            for p in registry[c]["params"]:
                assert p["name"] in args, (name, p["name"])
                assert "\n{} : ".format(p["name"]) in "\n" + doc, (name, p["name"])
    for name in ("sweep", "run", "commands", "read_rows"):
        assert ast.get_docstring(defs[name]), name


def test_signatures_and_defaults_are_the_registrys():
    registry = tg.commands()
    for name, commands in FUNCTIONS.items():
        sig = inspect.signature(getattr(tg, name))
        for c in commands:
            for p in registry[c]["params"]:
                q = sig.parameters[p["name"]]
                if p["required"]:
                    assert q.default is inspect.Parameter.empty, (name, p["name"])
                elif c == commands[0]:
                    assert q.default == p["default"], (name, p["name"])
        assert getattr(tg, name).__doc__.startswith(tg.SUMMARIES[name][:20])
