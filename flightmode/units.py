"""Constants and unit conversions: the one place they are defined.

Standard gravity comes from :mod:`scipy.constants`; the foot, knot, nautical mile and pound are the
exact decimal values of their international definitions (1959 yard and pound agreement; the
nautical mile of 1852 m), written as literals: ``scipy.constants.foot`` is computed as 12 x 0.0254
and lands one unit in the last place below 0.3048. Names carry the units they convert between:
multiply a value in the first unit by ``FT_M`` to get metres, divide metres by it to get feet.
"""

from __future__ import annotations

from scipy import constants as _c

G0_MPS2: float = _c.g  # standard gravity, 9.80665 m/s^2 (the g of accelerometer outputs)
FT_M: float = 0.3048  # international foot, exactly
IN_M: float = 0.0254  # inch, exactly
NM_M: float = 1852.0  # nautical mile, exactly
KT_MPS: float = NM_M / 3600.0  # knot: one nautical mile per hour
FPM_MPS: float = FT_M / 60.0  # ft/min -> m/s
KMH_MPS: float = 1000.0 / 3600.0  # km/h -> m/s
FPS_MPS: float = FT_M  # ft/s -> m/s
LB_KG: float = 0.45359237  # international avoirdupois pound, exactly
LBF_N: float = LB_KG * G0_MPS2  # pound-force: 4.4482216152605 N
SLUG_KG: float = LBF_N / FT_M  # slug: the mass a pound-force accelerates at 1 ft/s^2 (14.594 kg)
SLUG_FT3_KGM3: float = SLUG_KG / FT_M**3  # slug/ft^3 (JSBSim's density unit) -> kg/m^3 (515.38)
HPA_PA: float = _c.hecto  # hectopascal -> Pa (100)
PSI_PA: float = _c.psi  # 6894.757 Pa
