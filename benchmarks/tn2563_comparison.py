"""flexwing's aileron effectiveness against NACA TN 2563's straight wind-tunnel wing (issue 25).

    python benchmarks/tn2563_comparison.py [--panels 5]

The wing and the measurements are those of tests/tn2563.py (from the OpenAeroStruct control-
surface fork, which digitised them and reconstructed the stiffness). Prints, for each aileron
span, the measured and computed rolling-moment coefficient per degree at each dynamic pressure,
their ratio, both normalised by their value at 10 psf (the aeroelastic loss of effectiveness),
and flexwing's linear reversal pressure. A comparison to read, not a test of a number.
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import solver
from tests.tn2563 import DENSITY, MEASURED, PSF, flight, wing


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--panels", type=int, default=5, help="chordwise panels")
    parser.add_argument("--stations", type=int, default=21)
    args = parser.parse_args()
    options = solver.SolverOptions(chordwise_panels=args.panels)
    print(f"NACA TN 2563 straight wing, N = {args.stations}, k = {args.panels}")
    for fraction, points in MEASURED.items():
        model = wing(fraction, args.stations)
        reversal = solver.linear_reversal(model, "aileron", DENSITY, options)
        assert reversal.dynamic_pressure is not None
        print(
            f"aileron over the outer {100 * fraction:.0f} % of the semispan: flexwing's linear "
            f"reversal at {reversal.dynamic_pressure / PSF:.1f} psf"
        )
        print("   q [psf]   measured   flexwing  ratio   measured/10psf  flexwing/10psf")
        first = None
        for q, measured in points:
            (aileron,) = solver.control_effectiveness(model, flight(q), options)
            ours = aileron.coefficient_derivative
            first = first or (measured, ours)
            print(
                f"   {q:7.0f}  {measured:.6f}  {ours:.6f}  {ours / measured:5.3f}"
                f"   {measured / first[0]:13.3f}  {ours / first[1]:14.3f}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
