"""Rabbit (seed 003 §3.5): the spine of silicone ring discs, modelled quasi-statically.

plots — the stiffness against the discs' pre-compression (§3.5.4), the yaw turn (Fig. 3.27)
stiffening — E6: stiffening by pre-compressing the discs (§3.5.3–3.5.4)
yaw_turn — the upper body turned in yaw by the muscles (§3.5.4, Fig. 3.27)
"""
