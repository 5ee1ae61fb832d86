"""What the controller reads and when its command lands: encoders and the loop's delay.

ros2_control runs ``read() -> update() -> write()`` back to back once per control period
(ros-controls/ros2_control controller_manager/src/ros2_control_node.cpp, the ``while`` loop).
A hardware interface on a field bus latches the state at one bus cycle and the drives apply the
command written after it at the next (EtherCAT drives in synchronous mode do exactly this), so
the effort computed from the reading at ``t_k`` acts on the plant from ``t_(k+1)`` to
``t_(k+2)``. That is one period of delay on top of the zero-order hold; :class:`Sensing` turns
it on or off (``--no-delay``: an interface whose command lands within the same period).

With ``counts`` set, each rotary actuator has an encoder of that many counts per revolution: the
controller reads the actuator angle rounded to a whole count (the resolution at the joint is
``2 pi / (counts |n|)`` through a reduction ``n``) and estimates the speed by the finite
difference of two readings, as a hardware interface without a velocity sensor does.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from txtool.io.xmlio import InputError
from txtool.simulation.drive import Drive
from txtool.simulation.model import RobotModel

Reader = Callable[[np.ndarray, np.ndarray, np.ndarray, int], None]


@dataclass(frozen=True)
class Sensing:
    """Loop timing and measurement: ``delay`` of one control period, encoder ``counts``."""

    delay: bool = True
    counts: int | None = None

    def __post_init__(self) -> None:
        if self.counts is not None and self.counts < 1:
            raise InputError(f"--encoder-counts: must be at least 1, got {self.counts}")


@dataclass(frozen=True)
class Encoder:
    """Quantised actuator positions and finite-difference speeds, from the plant's joint state.

    ``step[i]`` is the resolution of actuator ``i`` (0 where it is not quantised: a linear
    actuator, i.e. a prismatic joint driven directly, has no revolutions to count).
    """

    counts: int
    step: np.ndarray
    pos_j2a: np.ndarray  # the robot's maps: actuator position = pos_j2a @ x + pos_j2a_c
    pos_j2a_c: np.ndarray
    vel_j2a: np.ndarray

    @property
    def linear(self) -> np.ndarray:
        return self.step == 0

    def reader(self, rows: np.ndarray, position: slice, speed: slice, dt: float) -> Reader:
        """``read(row, x, v, k)``: fill row ``k``'s reading from the plant's ``x`` (and ``v``).

        The first reading's speed is the true one (the plant starts at rest on the reference);
        later speeds are ``(reading_k - reading_(k-1)) / dt``.
        """
        matrix, constant, velocity = self.pos_j2a, self.pos_j2a_c, self.vel_j2a
        scale = np.where(self.linear, 1.0, self.step)
        inverse, rate = 1.0 / scale, 1.0 / dt
        linear = np.nonzero(self.linear)[0] if self.linear.any() else None
        previous = rows[:, position]
        raw = np.empty(len(scale))

        def read(row: np.ndarray, x: np.ndarray, v: np.ndarray, k: int) -> None:
            reading = row[position]
            np.dot(matrix, x, out=raw)
            np.add(raw, constant, out=raw)
            np.multiply(raw, inverse, out=reading)
            np.rint(reading, out=reading)
            reading *= scale
            if linear is not None:
                reading[linear] = raw[linear]
            if k == 0:
                row[speed] = velocity @ v
            else:
                out = row[speed]
                np.subtract(reading, previous[k - 1], out=out)
                out *= rate

        return read


def encoder(counts: int | None, plant: Drive, robot: RobotModel) -> Encoder | None:
    """Encoders of ``counts`` per revolution on the robot's actuators (None without counts).

    Actuators of transmissions are taken as rotary (a transmission to a prismatic joint has a
    reduction in rad/m); a prismatic joint driven directly has a linear actuator.
    """
    if counts is None:
        return None
    linear = np.zeros(plant.na, dtype=bool)
    for columns, rows, tmap in plant.blocks:
        if tmap is None and robot.kinds[columns[0]] == "prismatic":
            linear[rows] = True
    step = np.where(linear, 0.0, 2 * math.pi / counts)
    return Encoder(counts, step, plant.pos_j2a, plant.pos_j2a_c, plant.vel_j2a)
