"""The transmission model, numbers as the loaders read them, the robot parts that
transmissions refer to, and what a loader binds."""
