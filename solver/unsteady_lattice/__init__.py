"""Unsteady aerodynamics on the statics' own lattice: a vortex lattice whose wake is shed at the
trailing edge and convected with the stream, in the frequency domain (Katz and Plotkin, Low-
Speed Aerodynamics, 2nd ed., ch. 13; Hall, AIAA J. 32(12), 1994; Murua, Palacios and Graham,
Prog. Aerosp. Sci. 55, 2012). The panels as numbers (`panels`), the horseshoe's velocity
(`vortices`), the oscillating wake's influence (`wake`) and the circulation of harmonic motion,
whose zero-frequency limit is the static lattice's exactly (`circulation`).
"""
