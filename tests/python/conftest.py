"""Shared set-up of the dnurbs Python tests: the module comes from the build tree
(PYTHONPATH=<build>/python, set by ctest), source and build directories from the environment."""

import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("DNURBS_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("DNURBS_BINARY_DIR", SOURCE_DIR / "build"))


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def binary_dir():
    return BINARY_DIR
