"""Beam Bots (BB) DSL: export of transmissions, their actuators, topology, names and round trip."""
