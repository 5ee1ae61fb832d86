"""Robots that repeat a transmission under other names: each shape converted once, then copied."""
