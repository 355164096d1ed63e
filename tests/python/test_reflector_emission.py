"""extract_emissivity removes the IR reflector's own emission (Kirchhoff: S0_r = (1 − ε_r)·L_dw + ε_r·L_BB(T_r))
when given its emissivity and contact temperature; without them eq 17 reads that emission as downwelling."""
import numpy as np
import pytest

import tirpol
from tirpol import calibration, core

BAND = core.Band(8.0, 14.0)


def scene():
    l_dw, l_bb, l_r = BAND.radiance(240.0), BAND.radiance(295.0), BAND.radiance(285.0)
    s0 = np.empty((20, 40)); s1 = np.zeros((20, 40)); s2 = np.zeros((20, 40))
    s0[:, :20] = 0.9 * l_dw + 0.1 * l_r           # reflector, ε_r = 0.1 at 285 K
    s0[:, 20:] = 0.08 * l_dw + 0.92 * l_bb        # panel, ε_S0 = 0.92
    s1[:, 20:] = -0.03 * (l_bb - l_dw)            # ε_S1 = −0.03
    return {"S0": s0, "S1": s1, "S2": s2}


TARGETS = [{"name": "panel", "rect": [21, 1, 18, 18], "view_angle_deg": 40.0, "temperature_k": 295.0,
            "temperature_std_k": 0.0}]


def test_reflector_emission_is_removed():
    reflector = {"rect": [1, 1, 18, 18], "emissivity": 0.1, "temperature_k": 285.0}
    [eps] = calibration.extract_emissivity(scene(), reflector=reflector, targets=TARGETS, band=BAND)
    assert eps["l_dw_w_m2_sr"] == pytest.approx(BAND.radiance(240.0), abs=1e-4)
    assert eps["eps_s0"] == pytest.approx(0.92, abs=1e-5)
    assert eps["eps_s1"] == pytest.approx(-0.03, abs=1e-5)
    [naive] = calibration.extract_emissivity(scene(), reflector=[1, 1, 18, 18], targets=TARGETS, band=BAND)
    assert naive["eps_s0"] < 0.915


def test_reflector_emissivity_needs_its_temperature():
    with pytest.raises(tirpol.Error, match="needs the reflector's temperature"):
        calibration.extract_emissivity(scene(), reflector={"rect": [1, 1, 18, 18], "emissivity": 0.1},
                                       targets=TARGETS, band=BAND)
    with pytest.raises(tirpol.Error, match="unknown key 'temperature'"):
        calibration.extract_emissivity(scene(), reflector={"rect": [1, 1, 18, 18], "temperature": 285.0},
                                       targets=TARGETS, band=BAND)
    with pytest.raises(tirpol.Error, match="out of range"):
        calibration.extract_emissivity(scene(), reflector={"rect": [1, 1, 18, 18], "emissivity": 1.0,
                                                           "temperature_k": 285.0}, targets=TARGETS, band=BAND)
