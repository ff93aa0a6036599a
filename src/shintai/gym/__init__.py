"""Gymnasium environments over shintai's bodies and modules (``pip install shintai[gym]``).

``import shintai.gym`` registers:

==============================  =====================================================================
``shintai/SnakeTwoPoint-v0``    seed 001 §3.3: head and tail targets, joint-rate actions, mode switching on
                                or off (:mod:`shintai.gym.snake`)
``shintai/ClaPosture-v0``       seed 003 §4.7: Cla's muscle spine holds a bend, muscle length commands
                                (:mod:`shintai.gym.spine`)
``shintai/TricyclePedal-v0``    seed 000 ch. 3: HRP2 drives the tricycle to a goal, one Fig. 3.16 command sample
                                (handle and crank steps) per action, carried out by the active/passive limbs
                                (:mod:`shintai.gym.tricycle`)
``shintai/QuadrupedCrawl-v0``   seed 004 §4: TITAN-VIII to its destination past a wall and a low obstacle,
                                one walking cycle's displacement per action (:mod:`shintai.gym.quadruped`)
``shintai/VBoardRide-v0``       seed 000 ch. 6: HRP2 rides the V-BOARD, the agent its speed governor — (u_v, u_ω)
                                of Eq. 6.5 every 24 ms, balance and foot damping inside (:mod:`shintai.gym.vboard`)
``shintai/NinebotRide-v0``      seed 000 §7.3.3: HRP2 rides the Ninebot, the agent its speed controller C_v — u_v
                                of Eq. 6.5 every 24 ms, balance inside (:mod:`shintai.gym.ninebot`)
==============================  =====================================================================

Every environment renders ``rgb_array`` frames, resets from a seed, and states its spaces with units in its
module's docstring. Each wraps the same bodies and control modules the scenarios run.

Modules:

loop_env — A Gymnasium environment over a shintai Body and its modules, run by the shared Loop
riding — The common part of the humanoid's vehicle environments (seed 000 ch. 6–7): the agent takes the speed …
"""

from __future__ import annotations

try:
    import gymnasium
except ImportError as exc:  # the optional extra
    raise ImportError("shintai.gym needs gymnasium: pip install 'shintai[gym]'") from exc

ENVIRONMENTS = {
    "shintai/SnakeTwoPoint-v0": ("shintai.gym.snake:SnakeTwoPointEnv", 600),
    "shintai/ClaPosture-v0": ("shintai.gym.spine:ClaPostureEnv", 60),
    "shintai/TricyclePedal-v0": ("shintai.gym.tricycle:TricyclePedalEnv", 60),
    "shintai/QuadrupedCrawl-v0": ("shintai.gym.quadruped:QuadrupedCrawlEnv", 50),  # seed 004 §4.1.2: 50 cycles
    "shintai/VBoardRide-v0": ("shintai.gym.vboard:VBoardRideEnv", 500),  # vboard.EPISODE_STEPS: 12 s of 24 ms steps
    "shintai/NinebotRide-v0": ("shintai.gym.ninebot:NinebotRideEnv", 500),  # the same
}

for _id, (_entry, _steps) in ENVIRONMENTS.items():
    if _id not in gymnasium.registry:
        gymnasium.register(id=_id, entry_point=_entry, max_episode_steps=_steps)
