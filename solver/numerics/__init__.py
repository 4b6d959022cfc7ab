"""Solving the equations: evaluating them (`evaluation`, `factors`), one mesh's compiled
functions (`compiled`, `cache`, `warm`), Newton's method, the static-stability verdict and
continuation along the branch (`newton`, `stability`, `continuation`, `path`).
"""
