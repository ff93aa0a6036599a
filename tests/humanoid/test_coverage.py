"""Seed 000's coverage rows and the humanoid experiments' check kinds (issue 18)."""

import re

from shintai.humanoid.coverage import ROWS
from shintai.scenarios import registry


def humanoid_scenarios():
    registry.load_all()
    return {sid: sc for sid, sc in registry.SCENARIOS.items() if sid.startswith("humanoid.")}


def test_every_humanoid_experiment_covers_seed_000_rows_and_quotes_the_seed_in_its_reproduction_checks():
    keys = {row.key for row in ROWS}
    assert all(key.startswith("000:") for key in keys) and len(keys) == len(ROWS)
    for sid, sc in humanoid_scenarios().items():
        assert sc.covers and set(sc.covers) <= keys, sid
        for c in sc.checks:
            assert c.kind in ("reproduction", "consistency"), (sid, c.name or c.metric)
            if c.kind == "reproduction":  # quotes the thesis by section, never a spec label alone
                assert re.search(r"thesis §\d", c.basis) or c.basis.startswith("as "), (sid, c.name or c.metric)
                assert "spec §" not in c.basis, (sid, c.name or c.metric)


def test_rows_without_a_scenario_say_what_is_missing():
    covered = {key for sc in humanoid_scenarios().values() for key in sc.covers}
    for row in ROWS:
        if row.key not in covered:
            assert row.not_built, row.key
        else:
            assert row.difference or row.why_not, row.key  # every built row differs from the thesis somewhere
