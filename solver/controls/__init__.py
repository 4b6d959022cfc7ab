"""Control surfaces at work: the ailerons' antisymmetric response and the free roll (`roll`),
control effectiveness and reversal against airspeed (`effectiveness`).
"""
