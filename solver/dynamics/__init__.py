"""Vibration and flutter: the beam's natural modes (`modes`), strip theory's unsteady loads
(`unsteady`) and the p-k flutter analysis about the loaded wing (`flutter`).
"""
