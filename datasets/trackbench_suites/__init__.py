"""Shared suites plugin (in progress)."""
