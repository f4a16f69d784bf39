"""Cutting tools, rack and hob-profile derivation, hobbability and cutting simulation.

The package is laid out by the design card (DESIGN.md); its contents arrive with the hob issue.
"""
