"""Vehicles of seed 000: the tricycle (App. A.1.1) and the V-BOARD two-wheeled scooter (App. A.1.2)."""
