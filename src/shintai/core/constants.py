"""Physical constants shared by every body (one place each)."""

GRAVITY = 9.81  # m/s²: MuJoCo's default gravity, so analytic models and MuJoCo bodies agree
KGF_N = 9.80665  # N per kgf: the unit's definition (the spine thesis gives tensions in kgf)
