"""The International Standard Atmosphere (ICAO Doc 7488, identical to the U.S. Standard Atmosphere
1976 below 32 km): temperature, pressure and density against geopotential altitude, troposphere
(lapse rate -6.5 K/km to 11 km) and lower stratosphere (isothermal 216.65 K to 20 km). Vectorised;
SI. The one atmosphere of flightmode (JSBSim has its own inside the FDM)."""

from __future__ import annotations

import numpy as np
from scipy import constants as _c

T0_K = 288.15  # sea-level temperature
P0_PA = 101_325.0  # sea-level pressure
LAPSE_KPM = -0.0065  # troposphere lapse rate
H_TROPO_M = 11_000.0
R_AIR = _c.R / 0.0289644  # specific gas constant of dry air, J/(kg K) (molar mass 28.9644 g/mol)
BAROMETRIC_EXPONENT = -_c.g / (LAPSE_KPM * R_AIR)  # 5.2559: p = p0 (T / T0) ** this in the troposphere
T_TROPO_K = T0_K + LAPSE_KPM * H_TROPO_M  # 216.65 K
P_TROPO_PA = P0_PA * (T_TROPO_K / T0_K) ** BAROMETRIC_EXPONENT  # 22,632 Pa


def temperature_k(alt_m) -> np.ndarray:
    h = np.asarray(alt_m, float)
    return np.where(h < H_TROPO_M, T0_K + LAPSE_KPM * h, T_TROPO_K)


def pressure_pa(alt_m) -> np.ndarray:
    h = np.asarray(alt_m, float)
    tropo = P0_PA * (np.maximum(T0_K + LAPSE_KPM * h, 1.0) / T0_K) ** BAROMETRIC_EXPONENT
    strato = P_TROPO_PA * np.exp(-_c.g * (h - H_TROPO_M) / (R_AIR * T_TROPO_K))
    return np.where(h < H_TROPO_M, tropo, strato)


def pressure_altitude_m(p_pa) -> np.ndarray:
    """The altitude whose ISA pressure is ``p_pa``: :func:`pressure_pa` inverted in closed form, layer
    by layer (troposphere: h = (T0 / L) ((p / p0)^(1 / exp) - 1); stratosphere: logarithmic)."""
    p = np.asarray(p_pa, float)
    tropo = T0_K / LAPSE_KPM * ((p / P0_PA) ** (1.0 / BAROMETRIC_EXPONENT) - 1.0)
    strato = H_TROPO_M - R_AIR * T_TROPO_K / _c.g * np.log(p / P_TROPO_PA)
    return np.where(p > P_TROPO_PA, tropo, strato)


def density_kgpm3(alt_m) -> np.ndarray:
    return pressure_pa(alt_m) / (R_AIR * temperature_k(alt_m))
