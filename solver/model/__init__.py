"""The coupled equations, as CasADi graphs of one mesh: where each unknown and named parameter
slot sits (`layout`), the deformed lattice and the swept beam's kinematics (`geometry`), one
horseshoe vortex (`horseshoe`) and the lattice's induced-velocity kernels, symmetric (`vlm`) and
with the image half's flow as parameters (`flow_vlm`), the panels' tangency and loads
(`aerodynamics`), the beam's rows (`beam`), strip theory's induced velocities (`strip`), the
compiled functions' symbols (`symbols`), the induced velocities' chain rule (`induced`), the flow
model's outputs (`flow`), and the compiled functions with their version (`residual`: r = r0(x) +
q r1(x) and its exact Jacobians).
"""
