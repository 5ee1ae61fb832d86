"""Closed-loop check of a transmission config: ``txtool simulate``.

The plant is the robot with its own transmissions; a computed-torque controller reads and
commands the actuators through a candidate config. Entry points: :func:`run.simulate_one` and
:func:`jobs.execute` (results), :func:`app.main` (what the command prints and returns) and
:func:`demo.demo_runs`. The modules import numpy and pinocchio; import them only when simulating.
"""
