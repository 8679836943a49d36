"""Shared set-up of the dnurbs Python tests: the module comes from the build tree
(PYTHONPATH=<build>/python, set by ctest), source and build directories from the environment.

Usage recording: every public function, method, static method and property of the compiled
module is wrapped (at import, before any test) by a Python function that notes its qualified
name ("NurbsCurve.derivatives", "read_scene") and calls the original. At the end of a session
the names called are written to <build>/python_usage/<test file>.txt; test_binding_coverage.py
fails if a bound name is called by no test file."""

import functools
import inspect
import os
import pathlib

import pytest

import dnurbs

SOURCE_DIR = pathlib.Path(os.environ.get("DNURBS_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("DNURBS_BINARY_DIR", SOURCE_DIR / "build"))
USAGE_DIR = BINARY_DIR / "python_usage"

USED = set()


def _recording(name, function):
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        USED.add(name)
        return function(*args, **kwargs)
    return wrapper


def bound_members():
    """(qualified name, owner, attribute name, value) of every public binding of the module:
    module functions, and per class __init__, __call__, methods, static methods and properties
    (enumerations excluded: their values are constants; so are the slot __init__ of classes
    without a constructor, which only raise "No constructor defined")."""
    module = dnurbs._dnurbs
    for name, value in sorted(vars(module).items()):
        if name.startswith("_") or isinstance(value, (int, float, str)):
            continue
        if not inspect.isclass(value):
            if callable(value):
                yield name, module, name, value
            continue
        if hasattr(value, "__members__") or issubclass(value, BaseException):
            continue
        for member, attribute in sorted(vars(value).items()):
            if member.startswith("_") and member not in ("__init__", "__call__"):
                continue
            if type(attribute).__name__ == "wrapper_descriptor":
                continue  # the "No constructor defined" __init__ of classes built by functions
            yield f"{name}.{member}", value, member, attribute


def _install_recorders():
    for qualified, owner, member, value in list(bound_members()):
        if isinstance(value, property):
            getter = _recording(qualified, value.fget) if value.fget else None
            setter = _recording(qualified, value.fset) if value.fset else None
            setattr(owner, member, property(getter, setter, None, value.__doc__))
        elif isinstance(value, staticmethod):
            setattr(owner, member, staticmethod(_recording(qualified, value.__func__)))
        elif inspect.isclass(owner):
            # pybind11 methods are instancemethod objects around the C++ function.
            setattr(owner, member, _recording(qualified, getattr(value, "__func__", value)))
        else:
            wrapper = _recording(qualified, value)
            setattr(owner, member, wrapper)
            if getattr(dnurbs, member, None) is value:
                setattr(dnurbs, member, wrapper)


_install_recorders()


def pytest_sessionfinish(session):
    files = sorted({pathlib.Path(str(item.fspath)).stem for item in session.items})
    if not files:
        return
    USAGE_DIR.mkdir(parents=True, exist_ok=True)
    name = files[0] if len(files) == 1 else "session"
    (USAGE_DIR / f"{name}.txt").write_text("".join(f"{used}\n" for used in sorted(USED)))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def binary_dir():
    return BINARY_DIR
