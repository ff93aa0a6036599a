"""Coverage rows of seed 003 (Mizuuchi 2001) chapter 6 and Appendix C — the middle layer "nervous" — for
``shintai.nervous``.

Chapter 6 describes a system design and reports no experiment or measurement: Figs. 6.1–6.9 are architecture
diagrams, photographs of boards (JSK-D02, H8-08D), the processor layout on Cla, the software layers, the class
extension and the CAD conversion; the numbers it gives are specifications (serial links of 153.6 kbps on Cla and
38.4 kbps on the others, §6.3.1; I²C at up to about 714 kHz, §6.4.2; Kenta's 96 motors and 94 tension sensors,
§6.1), not results. Appendices B (H8 library) and D (VRML converter) are code. The one result figure is Fig. C.1.
Numbers are quoted from the Japanese seed ``003_8568e43d956eb469.txt``.
"""

from shintai.scenarios.coverage import Row

ROWS = (
    Row(
        key="003:figC.1",
        where="seed 003 App. C.2.2, Fig. C.1 (seqplugin, §6.3.4)",
        what="nervous's seqplugin plays a queue of targets given at once with the minjerksequence interpolation: "
             "time 0 → position 0, 250 ms → 60, 350 ms → 120, 600 ms → 60, 850 ms → 0",
        result="App. C.2.2: with minjerk or linear the velocity is zero at every queued posture; with "
               "minjerksequence, once a posture is second or later in the queue, 'その初期速度を 0 でなく前のキューと"
               "バランスするような速度にする'; Fig. C.1 plots the resulting position and velocity against time. The "
               "balancing rule is not written out and the plot carries no number beyond the commanded targets",
        difference="the balancing rule is ours (the time-weighted mean of the slopes into and out of a posture, "
                   "at every queued posture as the text says): with it the trace passes 120 at 350 ms still "
                   "rising and peaks at 132.8; the alternative that stops at turning points (via turning) stays "
                   "at 120 but is zero there. Fig. C.1's curve is not in the text, so its shape is not compared; "
                   "units taken as deg and ms",
    ),
)
