"""shintai (身体, "body"): one runtime that makes the robot bodies of four theses run, learn and evolve.

See ../shared/DESIGN.md for the architecture: a Body, Modules that add contributions to the command,
a Loop that runs them in parallel and a Switcher that runs exactly one of a set.
"""

__version__ = "0.1.0"
