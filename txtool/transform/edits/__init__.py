"""Edits: a change to a document said as byte ranges of the original and what replaces them."""
