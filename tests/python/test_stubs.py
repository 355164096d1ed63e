"""The .pyi stubs editors read describe the package as built: every public function and class of each
submodule is in its stub and every stub name exists, and everything public has a docstring for help()."""

import ast
import importlib
import inspect
import pathlib

import pytest

import tirpol

MODULES = ["acquisition", "calibration", "core", "fitting", "materials", "report", "simulation"]


def stub_names(module_name):
    path = pathlib.Path(tirpol.__file__).parent / f"{module_name}.pyi"
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    return names - {"Frame"}  # TypedDict describing grab()'s dict, not a runtime name


def runtime_names(module):
    return {n for n, v in vars(module).items()
            if not n.startswith("_") and (inspect.isclass(v) or callable(v)) and not inspect.ismodule(v)}


@pytest.mark.parametrize("module_name", MODULES)
def test_stub_lists_exactly_the_public_names(module_name):
    module = importlib.import_module(f"tirpol.{module_name}")
    assert runtime_names(module) == stub_names(module_name)


@pytest.mark.parametrize("module_name", MODULES)
def test_public_functions_have_docstrings(module_name):
    module = importlib.import_module(f"tirpol.{module_name}")
    assert module.__doc__
    for name in runtime_names(module):
        obj = getattr(module, name)
        if inspect.isclass(obj):
            continue  # classes: their methods carry the documentation
        assert obj.__doc__ and len(obj.__doc__.splitlines()[-1]) > 0, f"{module_name}.{name} has no docstring"
