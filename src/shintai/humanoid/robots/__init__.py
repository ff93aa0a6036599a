"""Robot models of seed 000: the HRP2-JSK-like humanoid (App. A.2.1) and Kenshiro's legs (§3.5.5)."""
