"""Every bound class and function is used by at least one test: the union of the names the other
test files called (recorded by conftest.py into <build>/python_usage/, one file per test file,
written when that file's session ends) must be every public binding of the module. A binding
added without a test that calls it fails here, naming it.

ctest runs this file after the others (fixture python_usage); run alone, or after a rebuild of
the module, it fails saying which test files have no fresh record."""

import pathlib

import dnurbs
from conftest import USAGE_DIR, bound_members

TESTS = pathlib.Path(__file__).resolve().parent


def test_every_binding_is_called_by_some_test():
    module_time = pathlib.Path(dnurbs._dnurbs.__file__).stat().st_mtime
    others = sorted(path.stem for path in TESTS.glob("test_*.py")
                    if path.stem != pathlib.Path(__file__).stem)
    fresh = {path.stem: path for path in USAGE_DIR.glob("*.txt")
             if path.stat().st_mtime >= module_time}
    if "session" not in fresh:  # else one pytest session ran the whole folder
        missing = [stem for stem in others if stem not in fresh]
        assert missing == [], ("no usage record newer than the module for these test files; "
                               "run `ctest -L python`: " + ", ".join(missing))
    used = set()
    for path in fresh.values():
        used.update(path.read_text().split())
    bound = {name for name, _, _, _ in bound_members()}
    assert len(bound) > 300  # the walk sees the whole module (367 names when this was written)
    assert sorted(bound - used) == []
