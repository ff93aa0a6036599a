"""SQ43 (seed 003 §3.2, §5.6): the quadruped with a foam spine.

body — the whole-body MuJoCo SQ43 (§3.2.2, §5.6)
constants — SQ43's numbers: the trot's gene ranges and weights, the design and levelling checks (§3.2, §5.6)
design — the spine design search: compass search over three vertebra angles (§3.2.3)
gaits — the statically planned crawl and its lift tests (§3.2.4–3.2.5), the GA trot's foot paths and fitness (§5.6)
levelling — the accelerometer levelling as a Module, and its rig (§3.2.4, Fig. 3.6)
standup — standing up from the belly: all legs at once, or front and hind in turns with the spine (§3.2.4, Fig. 3.9)
uneven — the crawl over uneven ground, paused and levelled after each touchdown (§3.2.4, Fig. 3.8)
plots — SQ43's pictures: the design search (cf. Fig. 3.4)
"""
