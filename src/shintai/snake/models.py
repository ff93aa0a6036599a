"""The snake's MuJoCo models for export (``shintai model``, :mod:`shintai.sim.export`)."""

from shintai.sim.export import model
from shintai.snake.caging import caging_scene
from shintai.snake.constants import CAGING_BOX, CH3_ROBOT
from shintai.snake.door import door_geometry, door_scene
from shintai.snake.mujoco_plant import snake_mjcf


@model("snake.ch3", "the n = 9 passive-wheel snake of seed 001 ch. 3 on a floor (snake.tracking --set plant=mujoco)")
def ch3_snake():
    return snake_mjcf(CH3_ROBOT)


@model("snake.caging", "the ch. 3 snake with the box it cages (snake.caging, §3.4.1)")
def caging():
    return snake_mjcf(CH3_ROBOT, scene=caging_scene(CAGING_BOX.xy))


@model("snake.door", "the 30-link snake and the spring-hinged door (snake.door, §3.4.3)")
def door():
    return snake_mjcf(door_geometry(), scene=door_scene())
