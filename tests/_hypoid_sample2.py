"""ISO 23509 Annex F, Sample 2 (the hypoid sample): its input data as ``BlankInput`` keywords, shared by the hypoid
tests (mm, rad)."""

import math

R = math.radians

SAMPLE2 = dict(z1=13, z2=42, b=30.0, beta_m=R(50.0), rc0=63.5, de2=170.0, a=15.0, f_alim=1.0, c_ham=0.35, k_d=2.0,
               k_c=0.125, k_t=0.1, jet=0.2, taper="given", theta_a2=R(1.0), theta_f2=R(4.0))
