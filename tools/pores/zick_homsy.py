"""Zick & Homsy (1982), J. Fluid Mech. 115, 13-26, Table 2: Stokes flow through a simple cubic
array of spheres, the reference the flow solver is verified against (tests/python/
test_pore_flow.py, results/flow_verification/)."""
import math

import numpy as np

# solid fraction c -> K, the drag F = 6 pi mu a K U on a sphere of radius a (U the superficial
# velocity)
SIMPLE_CUBIC = {0.027: 2.008, 0.064: 2.810, 0.125: 4.292, 0.216: 7.442, 0.343: 15.4,
                0.45: 28.1, 0.5236: 42.1}


def permeability(c):
    """(k, a) of the unit cell at solid fraction c (ln K interpolated linearly in c between the
    table's rows). Darcy: the force per volume on the spheres, F / 1, balances the pressure
    gradient mu U / k, so k = 1 / (6 pi a K), a = (3 c / (4 pi))^(1/3)"""
    table = sorted(SIMPLE_CUBIC.items())
    K = math.exp(np.interp(c, [t[0] for t in table], [math.log(t[1]) for t in table]))
    a = (3.0 * c / (4.0 * math.pi)) ** (1.0 / 3.0)
    return 1.0 / (6.0 * math.pi * a * K), a
