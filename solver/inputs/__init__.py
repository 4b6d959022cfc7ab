"""What a user gives: the wing (stations, chords, stiffness, airfoils, spar, mass, control
surfaces), the flight condition, the solver's options and the design problem, each field declared
once (`solver.fields`) and checked here, so the numerics never see bad data.
"""
