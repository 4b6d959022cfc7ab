"""The coupled equations: where each unknown and parameter sits (`layout`), the deformed lattice
and the swept beam's kinematics (`geometry`), the horseshoe kernel (`vlm`) and the residual
r = r0(x) + q r1(x) with its exact Jacobians, built as CasADi graphs (`residual`).
"""
