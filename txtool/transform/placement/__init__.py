"""Placement: where converted transmissions go, and how elements are laid out."""
