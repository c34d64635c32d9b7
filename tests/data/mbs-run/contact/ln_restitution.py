"""Effective restitution of the Hunt-Crossley contact law with Lankarani and
Nikravesh's hysteresis factor alpha = 3 (1 - e^2) / (4 v0): the 1-DOF impact
m d'' = -max(0, k d^n (1 + alpha d')) from d = 0, d' = v0, integrated with scipy's
DOP853 (rtol 1e-12) to the separation. The reference of tests/mbs-run/mechanics/test_contact.cpp
(HuntCrossleyRestitution), independent of mbs-run. Run: python3 ln_restitution.py
Printed (n, e, e_eff, e_eff - e, contact duration [s]) for m = 2 kg, k = 1e5, v0 = 1 m/s:
1.0 0.95 0.9535060451277123 0.003506045127712354 0.014052615222265988
1.0 0.9 0.9131766778060468 0.01317667780604681 0.014060497958639954
1.5 0.95 0.9535060451421367 ...   (the same e_eff: the law scales out k, m, v0)
"""
import numpy as np
from scipy.integrate import solve_ivp
def e_eff(e, n, m=2.0, k=1e5, v0=1.0):
    a = 3*(1-e*e)/(4*v0)
    def f(t, y):
        d, dd = y
        F = max(0.0, k*max(d,0)**n*(1+a*dd)) if d > 0 else 0.0
        return [dd, -F/m]
    ev = lambda t, y: y[0] if t > 1e-9 else 1.0
    ev.terminal = True; ev.direction = -1
    s = solve_ivp(f, [0, 1], [0.0, v0], rtol=1e-12, atol=1e-15, events=ev, method='DOP853')
    return -s.y_events[0][0][1]/v0, s.t_events[0][0]
for n in (1.0, 1.5):
    for e in (0.95, 0.9, 0.8, 0.5):
        ee, T = e_eff(e, n)
        print(n, e, ee, ee-e, T)
