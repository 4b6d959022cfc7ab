"""Gust loads of the flexible wing: the aircraft's plunge and the wing's modes with unsteady
aerodynamics as aerodynamic states (Wagner, Kuessner), discrete 1-cos gusts and continuous
turbulence (CS-25.341)."""
