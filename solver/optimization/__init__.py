"""Design: the reduced design functions and their exact gradients (`design_space`), and
IPOPT on them (`optimize`).
"""
