"""Rabbit (seed 003 §3.5): the spine of silicone ring discs, modelled quasi-statically.

plots — the stiffness against the discs' pre-compression (§3.5.4)
stiffening — E6: stiffening by pre-compressing the discs (§3.5.3–3.5.4)
"""
