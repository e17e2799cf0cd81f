"""Typed results: each function returns its own result class, a dict whose keys are also
attributes, whose docstring and stubs list the registry's result columns with their units —
and those columns are the report's keys."""

import ast
from pathlib import Path

import pytest

import tensegrity as tg
from tensegrity import results
from conftest import EXAMPLES

STUBS = Path(__file__).resolve().parents[1] / "python" / "tensegrity" / "__init__.pyi"


def lookup(report, dotted):
    value = report
    for part in dotted.split("."):
        value = value[part]
    return value


@pytest.mark.parametrize("call, cls", [
    (lambda: tg.statics(EXAMPLES / "prism.toml"), "StaticsResult"),
    (lambda: tg.simulate(EXAMPLES / "double_pendulum.toml", t_end=0.2), "SimulateResult"),
    (lambda: tg.toroid(), "ToroidResult"),
    (lambda: tg.roll(fidelity="rigid", t_end=1.2), "RollResult"),
    (lambda: tg.michell(complexity=3, planar=True, beta="30deg", phi="20deg"),
     "MichellResult"),
])
def test_a_result_is_its_class_and_its_columns_are_its_keys(call, cls):
    r = call()
    assert type(r).__name__ == cls and isinstance(r, tg.Result) and isinstance(r, dict)
    plain = r.to_dict()
    assert type(plain) is dict and plain == r
    name = cls[: -len("Result")].lower()
    found = 0
    for column, unit in results.columns(name):
        assert column in type(r).__doc__
        try:
            value = lookup(r, column)
        except KeyError:
            continue  # a field of another variant (a load solve, a 3-D truss, …)
        found += 1
        if "." not in column and column.isidentifier():
            assert getattr(r, column) is r[column]
        if unit and value is not None:
            assert isinstance(value, (int, float)), (column, value)
    # the documented fields are this report's, not another's
    assert found >= 0.6 * len(results.columns(name)), (found, len(results.columns(name)))
    with pytest.raises(AttributeError, match="has no field 'no_such_field'"):
        r.no_such_field


def test_the_stubs_type_every_result_and_every_function_returns_one():
    tree = ast.parse(STUBS.read_text())
    classes = {c.name: c for c in tree.body if isinstance(c, ast.ClassDef)}
    functions = {f.name: f for f in tree.body if isinstance(f, ast.FunctionDef)}
    for name in results.COMMANDS:
        cls_name = type(results.result_class(name)(())).__name__
        c = classes[cls_name]
        fields = {a.target.id for a in c.body if isinstance(a, ast.AnnAssign)}
        for column, _ in results.columns(name):
            if column.isidentifier():
                assert column in fields, (cls_name, column)
        for field, _, _ in results.EXTRA_FIELDS.get(name, ()):
            assert field in fields
        assert ast.unparse(functions[name].returns) == cls_name
    # the simulate and roll arrays are in their classes
    assert "contact_forces" in results.SimulateResult.__doc__
    assert "energy_J" in results.RollResult.__doc__
