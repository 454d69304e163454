"""The scenario models build their validators when first used, not at import: importing
:mod:`rancf.scenario` (every command line that reads a file does) builds none, and deferring the
build changes neither the JSON Schema of ``rancf schema`` nor what a file validates to."""

from __future__ import annotations

import json
import subprocess
import sys

from rancf.studies.common import example_path

#: Prints, as JSON, which tables have a built validator after ``import rancf.scenario`` (with
#: ``sys.argv[1] == "eager"``: after building every one), then the schema and the validated
#: shipped pendulum.
SCRIPT = """
import json, sys
from rancf.scenario import load_scenario, scenario_schema
from rancf.scenario.base import Table

def tables(cls):
    for sub in cls.__subclasses__():
        yield sub
        yield from tables(sub)

built = sorted({c.__name__ for c in tables(Table) if c.__pydantic_complete__})
if sys.argv[1] == "eager":  # every model built on its own, as before deferral
    for c in tables(Table):
        c.model_rebuild(force=True)
    built = sorted({c.__name__ for c in tables(Table) if c.__pydantic_complete__})
sc = load_scenario(sys.argv[2])
print(json.dumps([built, scenario_schema(), sc.model_dump(mode="json")]))
"""


def _run(mode: str) -> list:
    p = subprocess.run(
        [sys.executable, "-c", SCRIPT, mode, str(example_path("planar-pendulum"))],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(p.stdout.strip().splitlines()[-1])


def test_import_builds_no_validator_and_the_schema_is_that_of_eager_models():
    built, schema, data = _run("deferred")
    eager_built, eager_schema, eager_data = _run("eager")
    assert built == []
    assert len(eager_built) > 20  # the comparison is with models that were really built
    assert schema == eager_schema
    assert data == eager_data
