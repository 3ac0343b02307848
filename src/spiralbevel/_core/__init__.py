"""Private numerical core: pure functions on float64 arrays, mm and rad, xyz on the trailing axis.

No I/O, no plotting, no state. Kernels trust their input; validation happens at the public entry points.
"""
