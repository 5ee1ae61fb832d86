"""The lint pipeline: context, rules, suppressions, severities."""
