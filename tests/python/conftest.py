"""Shared fixtures of the Python API's tests: the pathlab command line the
module is compared with ($PATHLAB_CLI, set by CTest) and a private reference
cache per test."""

import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("PATHLAB_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("PATHLAB_CLI does not name the pathlab binary")

    def run(*args, check=True):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError("pathlab %s failed: %s" % (" ".join(map(str, args)),
                                                           result.stderr))
        return result

    return run


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("PATHLAB_CACHE", str(tmp_path / "cache"))


def cli_error(result):
    """The one-line message of a refused command, without its prefix."""
    assert result.returncode == 2, result.stderr
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("pathlab: error: "), line
    return line[len("pathlab: error: "):]
