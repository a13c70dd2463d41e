"""Shared by the tests of `import specula`: the CLI of the same build, run for reference numbers."""
import json
import os
import subprocess

import pytest


def cli(*args):
    """The CLI's JSON output of `specula ARGS --format json` (or its own --json)."""
    done = subprocess.run([os.environ["SPECULA_CLI"], *args], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def cli_error(*args):
    """The CLI's one-line error for a bad invocation (exit 2), without its 'specula: error: ' prefix."""
    done = subprocess.run([os.environ["SPECULA_CLI"], *args], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2, done.stdout
    return done.stderr.strip().removeprefix("specula: error: ")


def column(table, name):
    return [row[name] for row in table["rows"]]


@pytest.fixture(scope="session")
def specula():
    import specula as package
    return package
