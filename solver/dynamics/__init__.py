"""Vibration and flutter: the beam's natural modes (`modes`); the unsteady loads of small
oscillations, strip theory's and the quasi-3D lattice's (`unsteady`) and the unsteady vortex
lattice's (`lattice_loads`), with the latter's transfer functions for modes and gusts
(`aerodynamic_forces`); the equations of motion on the modes (`reduced`), the p-k method
(`pk`), the states linearised about (`linearisation`), the crossings (`onset`) and the flutter
analysis (`flutter`).
"""
