"""The coupled equations: where each unknown and parameter sits (`layout`), the deformed lattice
and the swept beam's kinematics (`geometry`), one horseshoe vortex (`horseshoe`) and the
lattice's induced-velocity kernels, symmetric (`vlm`) and with the image half's flow as
parameters (`flow_vlm`), and the residual r = r0(x) + q r1(x) with its exact Jacobians, built as
CasADi graphs (`residual`).
"""
