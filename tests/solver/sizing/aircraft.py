"""The aircraft the sizing tests fly: constants and a light aircraft of the normal category."""

G0 = 9.80665
RHO0 = 1.225
RHO_3000 = 0.90912  # [kg/m^3], the ISA at 3,000 m (geopotential), to 5 digits: 1e-5 where used

# A light aircraft of the normal category: 1,100 kg, 16.2 m^2, mean chord 1.5 m.
LIGHT = {
    "weights": [1100.0 * G0],
    "cl_max": 1.6,
    "cl_min": -1.0,
    "altitudes": [0.0, 3000.0],
    "wing_area": 16.2,
    "mean_chord": 1.5,
    "lift_slope": 5.0,
}
