"""The numbers of the BeBe unit's modules — one place per constant (DESIGN.md), each with its
thesis section or the reason it was chosen; grouped by the module that uses them."""

from __future__ import annotations


# --- bebe.body ---
MIDDLE = 2  # abdomen 1: where a human pushes "the middle of the spine" (Fig. 4.55)
# (lower region, upper region): 3 spans × 12 kinds = 36 muscles (thesis: 36). Chosen so that every
# joint is crossed and the head is moved by a neck-like span.
SPANS = ((0, 2), (2, 4), (3, 5))
