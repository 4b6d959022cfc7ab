"""What the solver returns, every type defined once with its units (`quantities`): the
equilibrium and its findings, sweeps and divergence, designs, control and roll answers, flutter,
the unsteady lattice's aerodynamic forces.
"""
