"""Views of transmissions: rich tables and the field-by-field comparison."""
