"""Hough baseline tracker plugin (in progress)."""
