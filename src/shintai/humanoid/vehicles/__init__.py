"""Vehicles of seed 000: the tricycle (App. A.1.1)."""
