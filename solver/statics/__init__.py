"""Static aeroelasticity: a wing at an alpha as modelled (`system`), its loads, the jig and the
branch from it, the verdict and findings of a converged state, divergence, trim, one flight
condition's answer (`solve`) and a sweep over airspeeds.
"""
