"""HEXAR."""
